// summary.json: the machine-readable record of a run.
#pragma once

#include <nlohmann/json.hpp>

#include "pipeline_model.hpp"

namespace touchcloud {

nlohmann::json make_summary(const ResolvedPipeline& pipeline, const RunResult& result, const RunOptions& options);

}  // namespace touchcloud
