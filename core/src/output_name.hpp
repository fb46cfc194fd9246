// The rule for a file name a stage writes, relative to the output folder.
// Private to the core.
#pragma once

#include <optional>
#include <string>

namespace touchcloud {

// The names of the staging folders a run writes into inside its output
// folder (.touchcloud-staging-<pid>): reserved, no output may use them.
inline constexpr const char* kStagingPrefix = ".touchcloud-staging-";

// Why `file_name` would leave the output folder (absolute, or a first
// component '..' after normalising) or lie in a staging folder, or nullopt.
// "..hidden.ply" stays.
std::optional<std::string> output_name_problem(const std::string& file_name);

// The placeholder the runtime replaces by the pipeline's name in output file
// parameters, when it loads the pipeline.
inline constexpr const char* kPipelineField = "{pipeline}";
// `file_name` with each "{pipeline}" replaced by the pipeline's name.
std::string with_pipeline_name(std::string file_name, const std::string& pipeline_name);
// The placeholder replaced by the name of the run's scene, so one pipeline
// run on a user's object (--scene) names its files after that object.
inline constexpr const char* kSceneField = "{scene}";
std::string with_scene_name(std::string file_name, const std::string& scene_name);

}  // namespace touchcloud
