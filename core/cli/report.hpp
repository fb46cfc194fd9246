// `touchcloud report` and `run --report`: the run folder read, the page written.
#pragma once

#include <filesystem>

#include "report_html.hpp"
#include "report_run_folder.hpp"

namespace touchcloud::cli {

// Writes the report of `run_dir` to `out_file` (empty: run_dir/report.html)
// under a temporary name, then renames it; returns the file written.
// InputError (nothing written) when run_dir holds no touchcloud run.
std::filesystem::path write_report(const std::filesystem::path& run_dir, const std::filesystem::path& out_file = {});

}  // namespace touchcloud::cli
