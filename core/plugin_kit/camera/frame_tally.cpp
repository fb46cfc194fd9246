#include "touchcloud/plugin_kit/camera/frame_tally.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::camera {

void SequenceGaps::see(std::int64_t sequence, std::optional<std::int64_t> first) {
  if (last_ && sequence > *last_ + 1) dropped_ += sequence - *last_ - 1;
  if (!last_ && first && sequence > *first) dropped_ += sequence - *first;
  last_ = sequence;
}

void FrameTally::declare_metrics(PortSet& ports, const std::string& item, const std::string& captured_doc) {
  ports.metric("frames_dropped", "frames",
               "frames lost so far: gaps in the sequence of frames processed (touchcloud stream shows it live)");
  ports.metric("latency_ms", "ms",
               "the " + item + " before's time from capture to the chain's end, live (touchcloud stream --view shows it)")
      .lower_is_better();
  ports.metric("frames_captured", "frames", captured_doc).final();
  ports.metric("frames_processed", "frames", item + "s handed to the chain").final();
  for (const char* p : {"p50", "p95", "p99"})
    ports.metric(std::string("latency_") + p + "_ms", "ms",
                 std::string(p) + " of the time from capture to the chain's end for the " + item + " (the next call)")
        .final()
        .lower_is_better();
  ports.metric("rate_fps", "frames/s", item + "s processed per second, first to last").final().higher_is_better();
}

void FrameTally::call_started(Clock::time_point now, RunContext& ctx) {
  if (previous_captured_at_) {
    latency_ms_.push_back(std::chrono::duration<double, std::milli>(now - *previous_captured_at_).count());
    ctx.metric("latency_ms", latency_ms_.back(), "ms");
  } else {
    first_at_ = now;
  }
}

void FrameTally::handed_on(Clock::time_point captured_at) {
  previous_captured_at_ = captured_at;
  ++processed_;
}

void FrameTally::finish(RunContext& ctx, std::int64_t captured) {
  const Clock::time_point now = Clock::now();
  if (previous_captured_at_)
    latency_ms_.push_back(std::chrono::duration<double, std::milli>(now - *previous_captured_at_).count());
  ctx.metric("frames_captured", static_cast<double>(captured), "frames");
  ctx.metric("frames_processed", static_cast<double>(processed_), "frames");
  std::vector<double> sorted = latency_ms_;
  std::sort(sorted.begin(), sorted.end());
  for (auto [name, q] : {std::pair{"p50", 0.50}, {"p95", 0.95}, {"p99", 0.99}}) {
    // Nearest rank: a value that was measured.
    const double v = sorted.empty() ? 0.0
                                    : sorted[static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size()))) - 1];
    ctx.metric(std::string("latency_") + name + "_ms", v, "ms");
  }
  const double span_s = processed_ > 0 ? std::chrono::duration<double>(now - first_at_).count() : 0.0;
  ctx.metric("rate_fps", processed_ > 0 && span_s > 0 ? static_cast<double>(processed_) / span_s : 0.0, "frames/s");
}

}  // namespace touchcloud::camera
