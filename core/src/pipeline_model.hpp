// The pipeline as parsed from YAML (PipelineDoc) and as resolved for running
// (ResolvedPipeline). Private to the core.
#pragma once

#include <any>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "touchcloud/error.hpp"
#include "touchcloud/pipeline.hpp"
#include "touchcloud/plugin_registry.hpp"

namespace touchcloud {

// ---- as written -------------------------------------------------------------

struct ParamDoc {
  std::string name;
  YAML::Node value;
  SourceLocation where;   // of the value
  bool from_command_line = false;
};

struct InputRefDoc {
  std::string port;       // the reading stage's input (empty for `until`)
  std::string stage, output;
  bool previous = false;  // `stage.output@previous`
  SourceLocation where;
};

struct NodeDoc {
  std::string id;
  SourceLocation where;
  bool is_loop = false;
  // a stage
  std::string plugin;
  SourceLocation plugin_where;
  std::vector<ParamDoc> params;
  std::vector<InputRefDoc> inputs;
  bool background = false;  // `background: true`
  // `own_scene: true`: the stage reads another scene than the pipeline's on
  // purpose; it keeps its own through `scene:` and --scene.
  bool own_scene = false;
  SourceLocation own_scene_where;
  // a loop
  std::int64_t max_iterations = 0;
  SourceLocation max_iterations_where;
  std::optional<InputRefDoc> until;
  std::vector<NodeDoc> body;
};

struct PipelineDoc {
  std::string name;
  std::filesystem::path file;
  // The top-level `scene: FILE` (or --scene): every stage with a `scene`
  // parameter takes it unless it sets its own.
  std::optional<ParamDoc> scene;
  std::vector<NodeDoc> nodes;
};

// Parses `file`; problems are appended to `diagnostics` (parsing goes on
// where it can, so one pass reports as much as possible).
PipelineDoc parse_pipeline(const std::filesystem::path& file, std::vector<Diagnostic>& diagnostics);
SourceLocation location_of(const YAML::Node& node, const std::filesystem::path& file);

// Converts a YAML value to a parameter of `spec`'s type; the error says why not.
std::optional<ParamValue> convert_param(const ParamSpec& spec, const YAML::Node& value, std::string& error);

// ---- as resolved ------------------------------------------------------------

struct ResolvedLoop;

struct ResolvedInput {
  std::string port;
  std::string key;                          // "stage.output"
  const ResolvedLoop* previous_of = nullptr;  // set: read the previous iteration of this loop
};

struct ResolvedStage {
  std::string id;
  SourceLocation where;
  const LoadedPlugin* plugin = nullptr;
  std::unique_ptr<Stage> stage;
  std::unique_ptr<ParameterSet> params;  // bound to *stage
  std::unique_ptr<PortSet> ports;
  std::map<std::string, ParamValue> values;           // every parameter with a value, defaults included
  std::map<std::string, SourceLocation> param_where;  // those set in the file or by --set
  std::vector<ResolvedInput> inputs;
  std::set<std::string> wanted_outputs;  // read by some stage or a loop's `until`
  // Of those, the ones read inside this stage's innermost loop (by a stage
  // in it, from the previous iteration, or as its `until`); the others are
  // read only after the loop.
  std::set<std::string> read_in_loop;
  std::unique_ptr<RunContext> context;
  // Runs on the pipeline's background thread, overlapping the stages after
  // it (pipeline_runner.cpp); its calls stay in order.
  bool background = false;
  int iteration = -1;  // of the innermost enclosing loop, as the runner reaches it
  StageTiming timing;  // check_s from the load; the rest from the last run
  std::vector<const ResolvedLoop*> loops;  // enclosing loops, outermost first
};

struct ResolvedNode {
  std::unique_ptr<ResolvedStage> stage;  // exactly one of these is set
  std::unique_ptr<ResolvedLoop> loop;
  const std::string& id() const;
};

struct ResolvedLoop {
  std::string id;
  SourceLocation where;
  std::int64_t max_iterations = 0;
  std::optional<std::string> until_key;  // "stage.output", a bool
  std::vector<ResolvedNode> body;        // in execution order
  std::vector<ResolvedStage*> stages;    // every stage inside, nested ones too
  int iterations_run = 0;
};

class ResolvedPipeline {
 public:
  std::string name;
  std::filesystem::path file;
  // The run's one scene (top-level `scene:` or --scene): its file and its
  // `name:` (the file's stem where it has none); empty without one.
  std::filesystem::path scene_file;
  std::string scene_name;
  std::vector<ResolvedNode> nodes;        // in execution order
  std::vector<ResolvedStage*> stages;     // every stage, in execution order
  std::vector<ResolvedLoop*> loops;
  // What the caller changed (--set, a sweep's --vary): summary.json records
  // them, and a report labels a folder's runs by the ones that differ.
  std::vector<Override> overrides;
  RunRecord record;
  double load_time_s = 0;  // Pipeline::load: parsing, loading plugins, checks
};

std::unique_ptr<ResolvedPipeline> resolve_pipeline(PipelineDoc doc, const std::vector<Override>& overrides,
                                                   PluginRegistry& registry);

}  // namespace touchcloud
