// Pipelines: YAML files that name stages, their plugins and parameters, how
// outputs feed inputs, and loops with a budget.
//
//   pipeline: downsample_cloud
//   stages:
//     - id: read
//       plugin: cloud_reader
//       params: {path: ../sample_clouds/fox_mask/ground_truth.pcd}
//     - id: down
//       plugin: downsample
//       params: {method: voxel, leaf_size_mm: 2.0}
//       inputs: {cloud: read.cloud}
//     - id: explore
//       loop:
//         max_iterations: 30          # the budget
//         until: plan.done            # optional: a bool output in the body
//         stages: [...]               # inputs may read `stage.port@previous`,
//                                     # the value from the previous iteration
#pragma once

#include <any>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "touchcloud/error.hpp"
#include "touchcloud/plugin_registry.hpp"
#include "touchcloud/run_context.hpp"

namespace touchcloud {

// `--set stage.param=value` from the command line.
struct Override {
  std::string key;              // "stage.param"
  std::string value;            // parsed as YAML, so lists read [1, 2, 3]
  std::string origin = "--set";  // the option it came from, for messages
};
Override parse_override(const std::string& text);  // "k=v"; InputError otherwise
// The key of an Override that sets the pipeline's scene (`--scene FILE`):
// every stage with a `scene` parameter takes it, except those that say
// `own_scene: true` or whose own was set by --set.
inline constexpr const char* kPipelineSceneKey = "scene";

class ResolvedPipeline;  // private to the runtime
struct RunOptions;
struct RunResult;

// A parsed, resolved and validated pipeline, ready to run. Every problem is
// reported at load, as InputError diagnostics with FILE:LINE:COL.
class Pipeline {
 public:
  // Parses, applies overrides, loads plugins, checks parameters, wiring and
  // input files (each stage's check hook). Throws InputError with all
  // diagnostics found.
  static Pipeline load(const std::filesystem::path& file, const std::vector<Override>& overrides,
                       PluginRegistry& registry);
  Pipeline(Pipeline&&) noexcept;
  Pipeline& operator=(Pipeline&&) noexcept;
  ~Pipeline();

  const std::string& name() const;
  const std::filesystem::path& file() const;
  // Every stage id and its resolved parameters ("id" -> "param" -> value).
  std::map<std::string, std::map<std::string, ParamValue>> parameters() const;
  // Every output ("stage.port") that some stage or a loop's `until` reads:
  // what a run computes anyway, so capturing it costs nothing extra.
  std::vector<std::string> wired_outputs() const;
  // Every metric its stages declare ("stage.metric" and the declaration), in
  // the stages' order: what a consumer may expect a run to report.
  std::vector<std::pair<std::string, MetricSpec>> declared_metrics() const;

 private:
  friend RunResult run_pipeline(Pipeline& pipeline, const RunOptions& options);
  explicit Pipeline(std::unique_ptr<ResolvedPipeline> impl);
  std::unique_ptr<ResolvedPipeline> impl_;
};

struct RunOptions {
  std::uint64_t seed = 0;
  std::filesystem::path out_dir;  // empty: write no files (outputs are refused)
  bool quiet = false;
  // Outputs ("stage.port") to hand back in RunResult::captured, for callers
  // that embed the runtime (the Python module); each is produced even when
  // no stage reads it. InputError for a stage or port the pipeline lacks.
  std::vector<std::string> capture;
  // Where stage log lines go (see RunSettings::log_sink); empty: std::clog.
  std::function<void(const std::string& line)> log_sink;
  // Called after each iteration of a top-level loop: its id, the iterations
  // run so far and its budget (the run's progress).
  std::function<void(const std::string& loop, std::int64_t done, std::int64_t budget)> on_loop_iteration;
  // Where a stage stands within one long call (RunContext::progress: a
  // training stage's epochs); called from the stage's thread.
  std::function<void(const std::string& stage, std::int64_t done, std::int64_t total, const std::string& unit)>
      on_stage_progress;
};

struct StageTiming {
  std::string id, plugin;
  double check_s = 0;  // at load, before the run (not in the run's wall time)
  double configure_s = 0, process_s = 0, finish_s = 0;
  std::size_t calls = 0;
};

struct RunResult {
  RunRecord record;
  std::vector<StageTiming> timings;  // in execution order
  double wall_time_s = 0;  // configure, the nodes, finish and the outputs
  // Before the run, in Pipeline::load: parsing, loading plugins and every
  // stage's checks (which may read and index data files).
  double load_time_s = 0;
  std::vector<std::pair<std::string, int>> loop_iterations;  // loop id, iterations run
  // RunOptions::capture's outputs, last value each (inside a loop: of the
  // last iteration); an output the stage did not produce is absent.
  std::map<std::string, std::any> captured;
  std::string summary_json;  // what summary.json holds (also without out_dir)
};

// Runs a loaded pipeline. Outputs go to a staging folder inside out_dir and
// are moved into place, with summary.json, only when the whole run succeeds.
// InputError: bad data found while running (exit 2); RunError: a stage failed
// (exit 1, the message names the stage).
RunResult run_pipeline(Pipeline& pipeline, const RunOptions& options);

}  // namespace touchcloud
