// touchcloud run PIPELINE [--set K=V]... [--seed N] [--out DIR]
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "progress_line.hpp"
#include "touchcloud/pipeline.hpp"
#include "report.hpp"
#include "run_printout.hpp"
#include "seed_option.hpp"
#include "verbs.hpp"

namespace touchcloud::cli {

namespace {

// The run's headline from the metrics' roles: its accuracy (Eq. 11) beside
// what accuracy alone hides, how much of the ground truth the reconstruction
// missed (completeness, F-score, coverage) of the same stage. Empty when no
// metric is of role accuracy.
std::string headline(const RunRecord& record) {
  const auto with_role = [&](MetricRole role, const std::string& stage) {
    std::vector<std::pair<std::string, const MetricSeries*>> found;
    for (const auto& [name, series] : record.metrics)
      if (series.spec.role == role && !series.values.empty() && (stage.empty() || name.rfind(stage, 0) == 0))
        found.emplace_back(name.substr(stage.size()), &series);
    return found;
  };
  std::string accuracy_name;
  for (const auto& [name, series] : record.metrics)
    if (series.spec.role == MetricRole::accuracy && !series.values.empty()) {
      accuracy_name = name;
      break;
    }
  if (accuracy_name.empty()) return "";
  const MetricSeries& accuracy = record.metrics.at(accuracy_name);
  const std::string stage = accuracy_name.substr(0, accuracy_name.find('.') + 1);
  std::ostringstream s;
  s << std::defaultfloat << std::setprecision(6) << "headline: " << accuracy_name << " "
    << accuracy.values.back() << (accuracy.spec.unit.empty() ? "" : " " + accuracy.spec.unit);
  const std::pair<MetricRole, const char*> beside[] = {
      {MetricRole::completeness, "completeness"}, {MetricRole::fscore, "F-score"}, {MetricRole::coverage, "coverage"}};
  std::ostringstream measured;
  measured << std::setprecision(6);
  // A role measured twice (coverage of the whole object and of what a press
  // from above sees) names each metric.
  for (const auto& [role, title] : beside) {
    const auto found = with_role(role, stage);
    for (std::size_t i = 0; i < found.size(); ++i) {
      const MetricSeries& m = *found[i].second;
      measured << (measured.tellp() > 0 ? ", " : "") << (i == 0 ? std::string(title) + " " : "")
               << m.values.back() << (m.spec.unit.empty() ? "" : " " + m.spec.unit)
               << (found.size() > 1 ? " (" + found[i].first + ")" : "");
    }
  }
  s << "; " << (measured.tellp() > 0 ? measured.str()
                                     : std::string("coverage not measured (the scoring stage computes no "
                                                   "completeness, F-score or recall: add them to its metrics)"));
  // Surface a mask dropped is missing, not better: said beside the score.
  for (const auto& [name, series] : record.metrics)
    if (series.spec.role == MetricRole::masked_points && !series.values.empty() && series.values.back() > 0)
      s << "; " << name << " " << series.values.back() << " (surface lost to a mask)";
  return s.str();
}

}  // namespace

Action* add_run_verb(CLI::App& app) {
  struct Options {
    std::string pipeline;
    std::vector<std::string> sets;
    std::string scene;
    std::uint64_t seed = 0;
    std::string out;
    bool quiet = false, progress = false;
    bool report = false;
    bool dry_run = false;
  };
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand("run", "Run a pipeline; write its outputs and summary.json into the output folder");
  cmd->add_option("pipeline", o.pipeline, "pipeline YAML file")->required();
  cmd->add_option("--set", o.sets, kSetHelp);
  cmd->add_option("--scene", o.scene, kSceneHelp);
  cmd->add_option("--seed", o.seed, "seed for every random draw; a seeded run reproduces bit for bit")
      ->check(seed_value())
      ->capture_default_str();
  cmd->add_option("--out", o.out, "output folder (default: out/<pipeline name>)");
  cmd->add_flag("-q,--quiet", o.quiet, "print no stage logs");
  cmd->add_flag("--progress", o.progress,
                "show the run's progress (iterations of its loop, a training stage's epochs, rate, time left) also "
                "when stderr is not a terminal (logs, CI)");
  cmd->add_flag("--report", o.report, "also write report.html (touchcloud report) into the output folder");
  cmd->add_flag("--dry-run", o.dry_run, kDryRunHelp);
  cmd->callback([] {
    action = [] {
      std::vector<Override> overrides;
      for (const auto& s : o.sets) overrides.push_back(parse_override(s));
      if (!o.scene.empty()) overrides.push_back({kPipelineSceneKey, o.scene, "--scene"});
      PluginRegistry registry;
      Pipeline p = Pipeline::load(o.pipeline, overrides, registry);
      RunOptions options;
      options.seed = o.seed;
      options.out_dir = output_folder(p, o.out);
      if (o.dry_run) {
        std::cout << o.pipeline << ": ok, not run (--dry-run; it would write " << options.out_dir.string() << ")\n";
        return kExitOk;
      }
      options.quiet = o.quiet;
      // Past a second, the top-level loop's iterations and a long stage's
      // own count on one line (stage logs printed above it), in a terminal
      // or when asked.
      ProgressLine progress(0, "", o.progress);
      options.log_sink = [&progress](const std::string& line) {
        progress.print_above(line.substr(0, line.size() - (!line.empty() && line.back() == '\n')));
      };
      options.on_loop_iteration = [&progress](const std::string& loop, std::int64_t done, std::int64_t budget) {
        progress.set(static_cast<std::size_t>(done), static_cast<std::size_t>(budget), loop + " iterations");
      };
      // A stage's progress within a long call (a trainer's epochs), after the loop's count.
      options.on_stage_progress = [&progress](const std::string& stage, std::int64_t done, std::int64_t total,
                                              const std::string& unit) {
        progress.set_step(stage, static_cast<std::size_t>(done), static_cast<std::size_t>(total), unit);
      };
      const RunResult r = run_pipeline(p, options);
      progress.finish();

      std::cout << "pipeline '" << p.name() << "' ran in " << std::fixed << std::setprecision(3) << r.wall_time_s
                << " s (seed " << o.seed << "), after " << r.load_time_s
                << " s loading plugins and checking stages\n";
      print_metrics_and_files(r, options.out_dir);
      if (o.report) std::cout << "wrote " << write_report(options.out_dir).string() << "\n";
      if (const std::string line = headline(r.record); !line.empty()) std::cout << line << "\n";
      return kExitOk;
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
