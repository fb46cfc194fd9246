// Streaming a pipeline (touchcloud stream, Python's touchcloud.stream): the
// run of run_pipeline, its top-level loop driven frame after frame by its
// source rather than by its budget.
#pragma once

#include <any>
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "touchcloud/pipeline.hpp"

namespace touchcloud {

struct StreamOptions {
  // Each top-level loop runs, whatever its max_iterations, until its
  // `until` (a recording's end), `stop` turning true (checked after each
  // frame) or `frames` frames.
  std::optional<std::int64_t> frames;
  const std::atomic<bool>* stop = nullptr;
  // Outputs of these data types ("frame_stamp") are captured too, as
  // RunOptions::capture's are.
  std::vector<std::string> capture_types;
  // After each frame: its number, the captured outputs' values it left, and
  // what the run has recorded so far (a source's dropped frames).
  std::function<void(std::int64_t frame, const std::map<std::string, std::any>& outputs, const RunRecord& record)>
      on_frame;
};

// Runs `pipeline` as run_pipeline does, streaming; summary.json adds each
// stage's latency percentiles over its calls (stages.N.latency_ms: p50, p95,
// p99). InputError when the pipeline has no top-level loop.
RunResult stream_pipeline(Pipeline& pipeline, const RunOptions& options, const StreamOptions& stream);

}  // namespace touchcloud
