#include "touchcloud/plugin_kit/camera/frame_feed.hpp"

#include <chrono>

#include "touchcloud/error.hpp"
#include "touchcloud/thread_end.hpp"

namespace touchcloud::camera {

FrameFeed::FrameFeed(std::unique_ptr<Capture> capture, std::size_t queue_frames, WhenBehind when_behind,
                     bool realtime, std::function<void(const Shot&)> on_capture)
    : capture_(std::move(capture)),
      capacity_(queue_frames),
      when_behind_(when_behind),
      realtime_(realtime),
      on_capture_(std::move(on_capture)) {
  thread_ = std::thread([this] { capture_loop(); });
}

FrameFeed::~FrameFeed() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameFeed::capture_loop() {
  const auto start = std::chrono::steady_clock::now();
  // A recording is read one frame ahead: each frame then knows whether
  // another follows (a stage's `done` needs no wait for the next frame's
  // time), and the next frame is decoded while this one waits to be due.
  const bool ahead = capture_->kind() == SourceKind::video_file || capture_->kind() == SourceKind::image_files;
  run_to_end(
      [&] {
        std::optional<Shot> shot = capture_->next();
        while (shot) {
          std::optional<Shot> following;
          if (ahead) {
            try {
              following = capture_->next();
            } catch (...) {  // the frames before a damaged one are still delivered
              deliver(std::move(*shot), start);
              throw;
            }
            if (following) shot->next_clock_s = following->clock_s;
            else shot->last = true;
          }
          if (!deliver(std::move(*shot), start)) return;
          shot = ahead ? std::move(following) : capture_->next();
        }
      },
      mutex_, changed_, error_, ended_);
}

bool FrameFeed::deliver(Shot shot, std::chrono::steady_clock::time_point start) {
  if (realtime_) {  // a recording delivered at the pace it was recorded, as a camera would
    const auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(shot.stamp.timestamp_s));
    std::unique_lock lock(mutex_);
    if (changed_.wait_until(lock, due, [&] { return stopping_; })) return false;
    shot.captured_at = due;  // captured when due, however late this thread woke
  }
  if (on_capture_) on_capture_(shot);
  std::unique_lock lock(mutex_);
  if (stopping_) return false;
  ++captured_;
  if (!first_sequence_) first_sequence_ = shot.stamp.sequence;
  if (queue_.size() >= capacity_) {
    if (when_behind_ == WhenBehind::drop_oldest) {
      queue_.pop_front();
      ++dropped_;
    } else {
      changed_.wait(lock, [&] { return stopping_ || queue_.size() < capacity_; });
      if (stopping_) return false;
    }
  }
  queue_.push_back(std::move(shot));
  lock.unlock();
  changed_.notify_all();
  return true;
}

bool FrameFeed::wait_for_frame_or_end(std::unique_lock<std::mutex>& lock, double timeout_s) {
  return changed_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                           [&] { return !queue_.empty() || ended_; });
}

std::optional<Shot> FrameFeed::next(double timeout_s) {
  std::unique_lock lock(mutex_);
  if (!wait_for_frame_or_end(lock, timeout_s))
    throw RunError("no frame from the " + std::string(describe(capture_->kind())) + " " + capture_->settings().source +
                   " within " + std::to_string(timeout_s) + " s (frame_timeout_s)");
  if (queue_.empty()) {
    if (error_) std::rethrow_exception(error_);
    return std::nullopt;
  }
  Shot shot = std::move(queue_.front());
  queue_.pop_front();
  lock.unlock();
  changed_.notify_all();
  return shot;
}

std::int64_t FrameFeed::captured() const {
  std::lock_guard lock(mutex_);
  return captured_;
}

std::optional<std::int64_t> FrameFeed::first_sequence() const {
  std::lock_guard lock(mutex_);
  return first_sequence_;
}

std::int64_t FrameFeed::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace touchcloud::camera
