// A folder of runs (a sweep's) as settings: runs given the same overrides
// are repeats of one setting (their seeds differ), and a setting is named by
// the values that were varied ("plan.strategy=random"), not by its folder.
#pragma once

#include <string>
#include <vector>

#include "report_run_folder.hpp"

namespace touchcloud::cli {

struct RunNames {
  std::vector<std::string> setting;  // per run: its setting's name
  std::vector<std::string> run;      // per run: the setting's name and the seed, unique in the folder
};

// Names by a sweep's --vary overrides (summary.json's `overrides`), else by
// the overrides that differ between the runs, else by the pipeline; the
// pipeline's name leads where the runs are of several pipelines.
RunNames name_runs(const std::vector<RunFolder>& runs);

}  // namespace touchcloud::cli
