// touchcloud sweep PIPELINE --vary K=V1,V2,... [--vary ...] [--repeats N] --out DIR
// Runs the pipeline over a grid of settings and seeds; records accuracy and
// time per run (sweep.csv), their means per setting (sweep_summary.csv), and
// plots accuracy against time with the Pareto front marked.
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "sweep_grid.hpp"
#include "touchcloud/pipeline.hpp"
#include "seed_option.hpp"
#include "touchcloud/file_write.hpp"
#include "verbs.hpp"

namespace fs = std::filesystem;

namespace touchcloud::cli {

namespace {

struct RunRow {
  std::size_t setting = 0;
  std::uint64_t seed = 0;
  double wall_time_s = 0;
  std::map<std::string, double> stage_time_s;  // process + configure + finish per stage
  std::map<std::string, double> metrics;       // final value of each metric
};

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string number(double v) { return format_value(ParamValue(v)); }

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

std::string csv_table(const std::vector<SweepAxis>& axes, const std::vector<std::vector<Override>>& settings,
                      const std::vector<RunRow>& rows, bool aggregate) {
  std::set<std::string> stages, metrics;
  for (const auto& r : rows) {
    for (const auto& [k, v] : r.stage_time_s) stages.insert(k);
    for (const auto& [k, v] : r.metrics) metrics.insert(k);
  }
  std::ostringstream out;
  out << "setting";
  for (const auto& a : axes) out << "," << csv_field(a.key);
  out << (aggregate ? ",runs" : ",seed") << ",wall_time_s";
  if (aggregate) out << ",wall_time_s_std";
  for (const auto& s : stages) out << ",time_" << s << "_s";
  for (const auto& m : metrics) out << "," << m << (aggregate ? "," + m + "_std" : "");
  out << "\n";

  const auto row_out = [&](std::size_t setting, const std::vector<const RunRow*>& group) {
    const auto mean_std = [&](auto get) {
      double sum = 0, sq = 0;
      for (const auto* r : group) sum += get(*r);
      const double mean = sum / static_cast<double>(group.size());
      for (const auto* r : group) sq += (get(*r) - mean) * (get(*r) - mean);
      return std::make_pair(mean, group.size() > 1 ? std::sqrt(sq / static_cast<double>(group.size() - 1)) : 0.0);
    };
    out << setting;
    for (const auto& o : settings[setting]) out << "," << csv_field(o.value);
    out << "," << (aggregate ? std::to_string(group.size()) : std::to_string(group[0]->seed));
    const auto wall = mean_std([](const RunRow& r) { return r.wall_time_s; });
    out << "," << number(wall.first);
    if (aggregate) out << "," << number(wall.second);
    for (const auto& s : stages) out << "," << number(mean_std([&](const RunRow& r) {
                                   auto it = r.stage_time_s.find(s);
                                   return it == r.stage_time_s.end() ? 0.0 : it->second;
                                 }).first);
    for (const auto& m : metrics) {
      bool all = true;
      for (const auto* r : group) all = all && r->metrics.count(m);
      if (!all) {
        out << "," << (aggregate ? "," : "");
        continue;
      }
      const auto ms = mean_std([&](const RunRow& r) { return r.metrics.at(m); });
      out << "," << number(ms.first);
      if (aggregate) out << "," << number(ms.second);
    }
    out << "\n";
  };
  if (!aggregate) {
    for (const auto& r : rows) row_out(r.setting, {&r});
  } else {
    for (std::size_t s = 0; s < settings.size(); ++s) {
      std::vector<const RunRow*> group;
      for (const auto& r : rows)
        if (r.setting == s) group.push_back(&r);
      if (!group.empty()) row_out(s, group);
    }
  }
  return out.str();
}

}  // namespace

Action* add_sweep_verb(CLI::App& app) {
  struct Options {
    std::string pipeline, out, accuracy, time = "wall_time_s";
    std::vector<std::string> vary, sets;
    int repeats = 1;
    std::uint64_t seed = 0;
  };
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand("sweep", "Run a pipeline over a grid of settings; accuracy and time per setting");
  cmd->add_option("pipeline", o.pipeline, "pipeline YAML file")->required();
  cmd->add_option("--vary", o.vary, "STAGE.PARAM=V1,V2,... (repeatable; every combination runs)")->required();
  cmd->add_option("--set", o.sets, "a fixed override for every run: STAGE.PARAM=VALUE");
  cmd->add_option("--repeats", o.repeats, "runs per setting, with seeds seed, seed+1, ...")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--seed", o.seed, "seed of the first repeat")->check(seed_value())->capture_default_str();
  cmd->add_option("--out", o.out, "output folder: sweep.csv, sweep_summary.csv, the plot, runs/")->required();
  cmd->add_option("--accuracy", o.accuracy,
                  "metric plotted as accuracy, lower is better (default: the first metric whose name has 'chamfer')");
  cmd->add_option("--time", o.time, "column plotted as time (wall_time_s or time_STAGE_s)")->capture_default_str();
  cmd->callback([] {
    action = [] {
      std::vector<SweepAxis> axes;
      for (const auto& v : o.vary) axes.push_back(parse_vary(v));
      std::vector<Override> fixed;
      for (const auto& s : o.sets) fixed.push_back(parse_override(s));
      auto settings = sweep_settings(axes);
      for (auto& s : settings) s.insert(s.begin(), fixed.begin(), fixed.end());

      // Every setting must load before anything runs.
      {
        PluginRegistry registry;
        for (const auto& s : settings) Pipeline::load(o.pipeline, s, registry);
      }
      for (auto& s : settings) s.erase(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(fixed.size()));

      const fs::path out = o.out;
      fs::create_directories(out / "runs");
      std::vector<RunRow> rows;
      const std::size_t total = settings.size() * static_cast<std::size_t>(o.repeats);
      for (std::size_t s = 0; s < settings.size(); ++s) {
        for (int r = 0; r < o.repeats; ++r) {
          auto overrides = fixed;
          overrides.insert(overrides.end(), settings[s].begin(), settings[s].end());
          PluginRegistry registry;
          Pipeline p = Pipeline::load(o.pipeline, overrides, registry);
          RunOptions options;
          options.seed = o.seed + static_cast<std::uint64_t>(r);
          options.out_dir = out / "runs" / ("setting" + std::to_string(s) + "_seed" + std::to_string(options.seed));
          options.quiet = true;
          const RunResult result = run_pipeline(p, options);
          RunRow row{s, options.seed, result.wall_time_s, {}, {}};
          for (const auto& t : result.timings) row.stage_time_s[t.id] = t.configure_s + t.process_s + t.finish_s;
          for (const auto& [name, series] : result.record.metrics) row.metrics[name] = series.values.back();
          rows.push_back(row);
          std::cerr << "[" << rows.size() << "/" << total << "]";
          for (const auto& ov : settings[s]) std::cerr << " " << ov.key << "=" << ov.value;
          std::cerr << " seed " << options.seed << ": " << std::fixed << std::setprecision(3) << result.wall_time_s
                    << " s\n" << std::defaultfloat;
        }
      }
      write_atomically(out / "sweep.csv", csv_table(axes, settings, rows, false));
      write_atomically(out / "sweep_summary.csv", csv_table(axes, settings, rows, true));
      std::cout << "wrote " << (out / "sweep.csv").string() << " (" << rows.size() << " runs) and "
                << (out / "sweep_summary.csv").string() << "\n";

      std::string accuracy = o.accuracy;
      if (accuracy.empty())
        for (const auto& [name, v] : rows.front().metrics)
          if (name.find("chamfer") != std::string::npos) {
            accuracy = name;
            break;
          }
      if (accuracy.empty()) {
        std::cout << "no plot: no metric has 'chamfer' in its name; choose one with --accuracy\n";
        return kExitOk;
      }
      if (!rows.front().metrics.count(accuracy))
        throw InputError("--accuracy " + accuracy + ": the pipeline reports no such metric");
      const fs::path script = plot_script();
      const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + (out / "sweep_summary.csv").string() +
                              "' --x '" + o.time + "' --y '" + accuracy + "' --out '" + (out / "accuracy_vs_time").string() + "'";
      if (!fs::exists(script) || std::system(cmd.c_str()) != 0)
        std::cout << "no plot: " << script.string() << " with /usr/bin/python3 and python3-matplotlib is needed "
                  << "(apt-get install python3-matplotlib); the CSV files are complete\n";
      else
        std::cout << "plotted " << accuracy << " against " << o.time << ": " << (out / "accuracy_vs_time.png").string()
                  << " and .svg\n";
      return kExitOk;
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
