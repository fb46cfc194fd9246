// touchcloud sweep PIPELINE --vary K=V1,V2,... [--vary ...] [--repeats N] --out DIR
// Runs the pipeline over a grid of settings and seeds; records accuracy and
// time per run (sweep.csv), their means per setting (sweep_summary.csv), and
// plots accuracy against time with the Pareto front marked.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "mpi_dispatch.hpp"
#include "progress_line.hpp"
#include "sweep_grid.hpp"
#include "report.hpp"
#include "sweep_rows.hpp"
#include "touchcloud/pipeline.hpp"
#include "seed_option.hpp"
#include "touchcloud/file_write.hpp"
#include "touchcloud/output_lock.hpp"
#include "verbs.hpp"

namespace fs = std::filesystem;

namespace touchcloud::cli {

namespace {

// Writes `text` to `file` through a temporary name, so a reader never sees half a file.
void write_atomically(const fs::path& file, const std::string& text) {
  const fs::path tmp = file.string() + ".tmp-" + std::to_string(::getpid());
  try {
    write_file(tmp, text);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, file);
}

fs::path plot_script() {
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  return exe.parent_path().parent_path() / "share/touchcloud/plot_sweep.py";
}

// One line, for a CSV cell and a progress line.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

Action* add_sweep_verb(CLI::App& app) {
  struct Options {
    std::string pipeline, out, accuracy, time = "wall_time_s", scene;
    std::vector<std::string> vary, sets;
    int repeats = 1;
    std::uint64_t seed = 0;
    bool resume = false, progress = false;
    bool report = false;
    bool dry_run = false;
  };
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand("sweep", "Run a pipeline over a grid of settings; accuracy and time per setting");
  cmd->add_option("pipeline", o.pipeline, "pipeline YAML file")->required();
  cmd->add_option("--vary", o.vary, "STAGE.PARAM=V1,V2,... (repeatable; every combination runs)")->required();
  cmd->add_option("--set", o.sets, "a fixed override for every run: STAGE.PARAM=VALUE");
  cmd->add_option("--scene", o.scene, kSceneHelp);
  cmd->add_option("--repeats", o.repeats, "runs per setting, with seeds seed, seed+1, ...")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--seed", o.seed, "seed of the first repeat")->check(seed_value())->capture_default_str();
  cmd->add_option("--out", o.out, "output folder: sweep.csv, sweep_summary.csv, the plot, runs/")->required();
  cmd->add_flag("--progress", o.progress,
                "show progress (runs done, rate, time left) also when stderr is not a terminal (logs, CI)");
  cmd->add_flag("--resume", o.resume,
                "keep the successful runs an earlier, stopped sweep left in DIR/sweep.csv and run only the others");
  cmd->add_option("--accuracy", o.accuracy,
                  "STAGE.METRIC plotted as accuracy, better as its declaration says (default: the pipeline's first "
                  "metric of role accuracy)");
  cmd->add_flag("--report", o.report, "also write report.html (touchcloud report of the sweep's folder) into --out");
  cmd->add_option("--time", o.time, "column plotted as time (wall_time_s or time_STAGE_s)")->capture_default_str();
  cmd->add_flag("--dry-run", o.dry_run, kDryRunHelp);
  cmd->callback([] {
    action = [] {
      std::vector<SweepAxis> axes;
      for (const auto& v : o.vary) axes.push_back(parse_vary(v));
      std::vector<Override> fixed;
      for (const auto& s : o.sets) fixed.push_back(parse_override(s));
      if (!o.scene.empty()) fixed.push_back({kPipelineSceneKey, o.scene, "--scene"});
      auto settings = sweep_settings(axes);
      for (auto& s : settings) s.insert(s.begin(), fixed.begin(), fixed.end());

      // Every setting must load before anything runs. The accuracy plotted,
      // unless named: the first metric a stage declares with role accuracy.
      std::string accuracy = o.accuracy;
      std::optional<MetricSpec> accuracy_spec;
      {
        PluginRegistry registry;
        for (const auto& s : settings) {
          const Pipeline p = Pipeline::load(o.pipeline, s, registry);
          std::string declared;
          for (const auto& [name, spec] : p.declared_metrics()) {
            if (!accuracy_spec && (o.accuracy.empty() ? spec.role == MetricRole::accuracy : name == o.accuracy))
              accuracy = name, accuracy_spec = spec;
            declared += (declared.empty() ? "" : ", ") + name;
          }
          if (!o.accuracy.empty() && !accuracy_spec)
            throw InputError("--accuracy " + o.accuracy + ": no stage of the pipeline declares such a metric (" +
                             declared + ")");
        }
      }
      for (auto& s : settings) s.erase(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(fixed.size()));
      if (o.dry_run) {
        std::cout << o.pipeline << ": ok, " << settings.size() << " settings x " << o.repeats
                  << " repeats, not run (--dry-run)\n";
        return kExitOk;
      }

      const fs::path out = o.out;
      // The whole sweep holds its folder, as a run holds its own: a second
      // sweep or run into it is refused (exit 2) while this one runs.
      std::optional<OutputFolderLock> lock;
      if (launched_rank() == 0) lock.emplace(out);
      const std::size_t repeats = static_cast<std::size_t>(o.repeats), total = settings.size() * repeats;
      // Run `job` is setting job / repeats with seed o.seed + job % repeats: the order of sweep.csv.
      const auto seed_of = [&](std::size_t job) { return o.seed + static_cast<std::uint64_t>(job % repeats); };
      const auto describe = [&](std::size_t job) {
        return "setting " + std::to_string(job / repeats) + " seed " + std::to_string(seed_of(job));
      };

      // --resume: the runs sweep.csv already holds (successful ones) are not run again.
      std::map<std::size_t, RunRow> rows;
      if (o.resume && launched_rank() == 0 && fs::exists(out / "sweep.csv"))
        for (auto& row : read_sweep_csv(out / "sweep.csv", axes, settings)) {
          if (row.seed < o.seed || row.seed - o.seed >= repeats)
            throw InputError("--resume: seed " + std::to_string(row.seed) + " is not one of this sweep's (" +
                             std::to_string(o.seed) + " to " + std::to_string(o.seed + repeats - 1) + ")",
                             {(out / "sweep.csv").string()});
          if (row.error.empty()) rows[row.setting * repeats + (row.seed - o.seed)] = std::move(row);
        }
      const std::size_t resumed = rows.size();
      std::vector<std::size_t> jobs;
      for (std::size_t job = 0; job < total; ++job)
        if (!rows.count(job)) jobs.push_back(job);

      // Any rank runs any job; its row comes back to rank 0.
      const auto work = [&](std::size_t job) {
        RunRow row;
        row.setting = job / repeats;
        row.seed = seed_of(job);
        try {
          auto overrides = fixed;
          overrides.insert(overrides.end(), settings[row.setting].begin(), settings[row.setting].end());
          PluginRegistry registry;
          Pipeline p = Pipeline::load(o.pipeline, overrides, registry);
          RunOptions options;
          options.seed = row.seed;
          options.out_dir = out / "runs" / ("setting" + std::to_string(row.setting) + "_seed" + std::to_string(row.seed));
          options.quiet = true;
          const RunResult result = run_pipeline(p, options);
          row.wall_time_s = result.wall_time_s;
          for (const auto& t : result.timings) row.stage_time_s[t.id] = t.configure_s + t.process_s + t.finish_s;
          for (const auto& [name, series] : result.record.metrics) row.metrics[name] = series.values.back();
        } catch (const std::exception& e) {
          row.error = one_line(e.what());
          if (row.error.empty()) row.error = "failed";
        }
        return serialise(row);
      };

      RankTeam team;
      if (team.rank() == 0) {
        std::error_code ec;
        fs::create_directories(out / "runs", ec);
        if (ec) throw InputError("cannot create the output folder " + (out / "runs").string() + ": " + ec.message());
      }
      // Rank 0 saves what is complete (atomically, at most once a second), so
      // a job stopped half way leaves a sweep.csv that --resume completes.
      const auto table = [&] {
        std::vector<RunRow> ordered;
        for (const auto& [job, row] : rows) ordered.push_back(row);
        return ordered;
      };
      std::atomic<std::size_t> saved{resumed};  // read by the stop message, from rank 0's dispatch thread
      auto last_save = std::chrono::steady_clock::now();
      // Rank 0 counts every rank's runs.
      std::optional<ProgressLine> progress;
      if (team.rank() == 0) progress.emplace(jobs.size(), "runs", o.progress);
      const auto finished = [&](std::size_t job, const RunPlace& place, const std::string& text) {
        RunRow row = deserialise(text);
        row.rank = place.rank;
        row.host = place.host;
        std::ostringstream line;
        line << "[" << rows.size() + 1 << "/" << total << "]";
        for (const auto& ov : settings[row.setting]) line << " " << ov.key << "=" << ov.value;
        line << " seed " << row.seed << ": ";
        if (row.error.empty())
          line << std::fixed << std::setprecision(3) << row.wall_time_s << " s" << std::defaultfloat;
        else
          line << "failed: " << row.error;
        line << (team.size() > 1 ? " (rank " + std::to_string(place.rank) + ")" : "");
        progress->print_above(line.str());
        progress->done_one();
        rows[job] = std::move(row);
        if (std::chrono::steady_clock::now() - last_save > std::chrono::seconds(1)) {
          write_atomically(out / "sweep.csv", csv_table(axes, settings, table(), false));
          saved = rows.size();
          last_save = std::chrono::steady_clock::now();
        }
      };
      const auto on_stop = [&] {
        return (out / "sweep.csv").string() + " holds " + std::to_string(saved) +
               " finished runs; run the same command with --resume to run the others";
      };
      team.run(jobs, work, finished, describe, on_stop);
      if (team.rank() != 0) return kExitOk;  // rank 0 writes every output
      progress->finish();

      const std::vector<RunRow> all = table();
      write_atomically(out / "sweep.csv", csv_table(axes, settings, all, false));
      write_atomically(out / "sweep_summary.csv", csv_table(axes, settings, all, true));
      std::cout << "wrote " << (out / "sweep.csv").string() << " (" << all.size() << " runs";
      if (resumed > 0) std::cout << ", " << resumed << " of them from before (--resume)";
      std::cout << ") and " << (out / "sweep_summary.csv").string() << "\n";
      std::vector<const RunRow*> failed;
      for (const auto& r : all)
        if (!r.error.empty()) failed.push_back(&r);
      const RunRow* first_ok = nullptr;
      for (const auto& r : all)
        if (r.error.empty() && !first_ok) first_ok = &r;

      // A failed run is a row with its error, the others go on; the exit status says so.
      const auto status = [&] {
        for (const auto* r : failed)
          std::cerr << "touchcloud: error: " << describe(r->setting * repeats + (r->seed - o.seed)) << ": " << r->error
                    << "\n";
        if (failed.empty()) return kExitOk;
        std::cerr << "touchcloud: error: " << failed.size() << " of " << all.size()
                  << " runs failed (their rows in sweep.csv say why); the rest ran\n";
        return kExitRunFailed;
      };
      if (!first_ok) return status();
      if (o.report) std::cout << "wrote " << write_report(out).string() << "\n";
      if (!accuracy_spec) {
        std::cout << "no plot: no stage declares a metric of role accuracy; choose one with --accuracy\n";
        return status();
      }
      if (!first_ok->metrics.count(accuracy))
        throw InputError("--accuracy " + accuracy + ": declared, but the runs reported no value of it");
      const fs::path script = plot_script();
      const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + (out / "sweep_summary.csv").string() +
                              "' --x '" + o.time + "' --y '" + accuracy + "' --y-unit '" + accuracy_spec->unit +
                              "' --y-direction " + to_string(accuracy_spec->direction) + " --out '" +
                              (out / "accuracy_vs_time").string() + "'";
      if (!fs::exists(script) || std::system(cmd.c_str()) != 0)
        std::cout << "no plot: " << script.string() << " with /usr/bin/python3 and python3-matplotlib is needed "
                  << "(apt-get install python3-matplotlib); the CSV files are complete\n";
      else
        std::cout << "plotted " << accuracy << " against " << o.time << ": " << (out / "accuracy_vs_time.png").string()
                  << " and .svg\n";
      return status();
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
