// Capture on its own thread, into a bounded queue the stage takes frames
// from. When processing falls behind a full queue either holds the camera
// back (block: nothing is lost, for files) or loses its oldest frame (drop
// oldest: the newest frame is processed, for live cameras); each frame lost
// is counted. A recording (a video file, image files) is read one frame
// ahead, so each frame says whether it is the last; `realtime` delivers its
// frames at the pace they were recorded, each stamped with the time it was
// due, as a camera would have captured it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "touchcloud/plugin_kit/camera/capture.hpp"

namespace touchcloud::camera {

enum class WhenBehind { block, drop_oldest };

class FrameFeed {
 public:
  // `on_capture` (may be empty) sees every frame captured, on the capture
  // thread, before it is queued (a recording keeps what processing drops).
  FrameFeed(std::unique_ptr<Capture> capture, std::size_t queue_frames, WhenBehind when_behind, bool realtime,
            std::function<void(const Shot&)> on_capture = {});
  ~FrameFeed();  // stops the capture thread
  FrameFeed(const FrameFeed&) = delete;
  FrameFeed& operator=(const FrameFeed&) = delete;

  // The oldest queued frame, waiting at most `timeout_s` for one; none at the
  // end of the source. Rethrows the capture thread's error; RunError when
  // nothing comes in time.
  std::optional<Shot> next(double timeout_s);
  std::int64_t captured() const;
  std::int64_t dropped() const;  // lost from a full queue
  std::optional<std::int64_t> first_sequence() const;  // of the first frame captured
  SourceKind source_kind() const { return capture_->kind(); }
  const std::string& source() const { return capture_->settings().source; }

 private:
  void capture_loop();
  // Queues `shot` (in realtime, at its due time, stamped with it); false
  // when the feed is stopping.
  bool deliver(Shot shot, std::chrono::steady_clock::time_point start);
  bool wait_for_frame_or_end(std::unique_lock<std::mutex>& lock, double timeout_s);

  std::unique_ptr<Capture> capture_;
  const std::size_t capacity_;
  const WhenBehind when_behind_;
  const bool realtime_;
  const std::function<void(const Shot&)> on_capture_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Shot> queue_;
  std::int64_t captured_ = 0, dropped_ = 0;
  std::optional<std::int64_t> first_sequence_;
  bool ended_ = false, stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace touchcloud::camera
