// What `run` and `stream` print and where they write: the output folder a
// pipeline gets by default, each metric's last value and the files written.
#pragma once

#include <filesystem>
#include <string>

#include "touchcloud/pipeline.hpp"

namespace touchcloud::cli {

// `out` when given, else out/<pipeline name>; InputError for a name that
// cannot name a folder there.
std::filesystem::path output_folder(const Pipeline& pipeline, const std::string& out);
// Each metric's last value, one a line, then the files written to `out_dir`.
void print_metrics_and_files(const RunResult& result, const std::filesystem::path& out_dir);

}  // namespace touchcloud::cli
