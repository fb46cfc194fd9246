// What a live source reports of the frames it handed on: frames lost as
// gaps in a camera's sequence numbers, the time from capture to the
// chain's end (the source's next call) and the sustained rate. Shared by
// camera_source and stereo_camera_source, which declare the same metrics.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "touchcloud/ports.hpp"
#include "touchcloud/run_context.hpp"

namespace touchcloud::camera {

using Clock = std::chrono::steady_clock;

// One camera's sequence numbers: a step of more than one is frames lost.
class SequenceGaps {
 public:
  // Counts the gap before `sequence`; before the first one seen, the gap
  // from `first`, the first sequence number the camera delivered (frames
  // lost from the queue before anything was taken from it).
  void see(std::int64_t sequence, std::optional<std::int64_t> first = std::nullopt);
  std::int64_t dropped() const { return dropped_; }

 private:
  std::optional<std::int64_t> last_;
  std::int64_t dropped_ = 0;
};

class FrameTally {
 public:
  // frames_dropped, latency_ms (live), frames_captured, frames_processed,
  // latency_p50/p95/p99_ms and rate_fps; `item` names what is handed on
  // ("frame", "pair").
  static void declare_metrics(PortSet& ports, const std::string& item, const std::string& captured_doc);

  // At the start of each call: the item handed on before has been through
  // the chain (its latency_ms reported).
  void call_started(Clock::time_point now, RunContext& ctx);
  // An item handed to the chain, captured at `captured_at`.
  void handed_on(Clock::time_point captured_at);
  std::int64_t processed() const { return processed_; }
  // frames_captured (given), frames_processed, the latency percentiles and
  // the rate, at the run's end (the last item's latency counted then).
  void finish(RunContext& ctx, std::int64_t captured);

 private:
  std::vector<double> latency_ms_;
  std::optional<Clock::time_point> previous_captured_at_;
  Clock::time_point first_at_;
  std::int64_t processed_ = 0;
};

}  // namespace touchcloud::camera
