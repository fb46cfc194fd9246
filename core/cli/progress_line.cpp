#include "progress_line.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>

namespace touchcloud::cli {

namespace {

std::string duration_text(double s) {
  char buf[32];
  if (s < 90) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 5400) std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  else std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

// In a terminal: redrawn 4 times a second, from 1 s on (a short batch shows
// nothing). In a log (--progress): a line every 5 s, and the last at the end.
constexpr std::chrono::milliseconds kTerminalPeriod{250}, kLogPeriod{5000};

}  // namespace

std::string progress_text(std::size_t done, std::size_t total, double elapsed_s, const std::string& noun,
                          std::size_t done_at_start) {
  // A total of 0: none known (a camera's frames).
  std::string text = std::to_string(done) + (total > 0 ? "/" + std::to_string(total) : std::string()) + " " + noun;
  if (done <= done_at_start || !(elapsed_s > 0)) return text;
  const double rate = static_cast<double>(done - done_at_start) / elapsed_s;
  char buf[64];
  std::snprintf(buf, sizeof buf, ", %.3g %s/s", rate, noun.c_str());
  text += buf;
  if (total > 0 && done < total) text += ", about " + duration_text(static_cast<double>(total - done) / rate) + " left";
  return text;
}

ProgressLine::ProgressLine(std::size_t total, std::string noun, bool forced, bool enabled)
    : total_(total), noun_(std::move(noun)), in_place_(::isatty(STDERR_FILENO) == 1) {
  if (enabled && (in_place_ || forced)) ticker_ = std::thread([this] { tick(); });
}

ProgressLine::~ProgressLine() { finish(); }

void ProgressLine::stage(const std::string& what) {
  std::lock_guard lock(mutex_);
  what_ = what;
}

void ProgressLine::done_one() {
  std::lock_guard lock(mutex_);
  ++done_;
}

void ProgressLine::set(std::size_t done, std::size_t total, const std::string& noun) {
  std::lock_guard lock(mutex_);
  if (noun != noun_) start_ = Clock::now();  // another loop: its own rate
  if (done != done_ || noun != noun_) step_.reset();  // the step's count was of the last iteration
  done_ = done, total_ = total, noun_ = noun;
}

void ProgressLine::set_step(const std::string& step, std::size_t done, std::size_t total, const std::string& noun) {
  std::lock_guard lock(mutex_);
  // A new step, or the same one counting again from below: its rate starts now.
  if (!step_ || step_->name != step || step_->noun != noun || done < step_->done)
    step_ = Step{step, noun, done, total, done, Clock::now()};
  step_->done = done, step_->total = total;
}

std::string ProgressLine::text_locked() const {
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  std::string text = noun_.empty() && total_ == 0 ? "" : progress_text(done_, total_, since(start_), noun_);
  if (step_)
    text += (text.empty() ? "" : "; ") + step_->name + ": " +
            progress_text(step_->done, step_->total, since(step_->start), step_->noun, step_->done_at_start);
  return text + (what_.empty() ? "" : "; " + what_);
}

void ProgressLine::print_above(const std::string& line) {
  std::lock_guard lock(mutex_);
  if (in_place_ && drawn_) std::cerr << "\r\033[K";
  std::cerr << line << "\n";
  if (in_place_ && drawn_) std::cerr << text_locked();
  std::cerr << std::flush;
}

void ProgressLine::finish() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

void ProgressLine::tick() {
  std::unique_lock lock(mutex_);
  const auto period = in_place_ ? kTerminalPeriod : kLogPeriod;
  while (!wake_.wait_for(lock, period, [this] { return stopped_; })) {
    if (in_place_ && Clock::now() - start_ < std::chrono::seconds(1)) continue;
    if (text_locked().empty()) continue;  // nothing counted yet (a run without a loop, before its stage reports)
    if (in_place_)
      std::cerr << "\r\033[K" << text_locked() << std::flush;
    else
      std::cerr << "progress: " << text_locked() << "\n" << std::flush;
    drawn_ = true;
  }
  if (in_place_ && drawn_) std::cerr << "\r\033[K" << std::flush;
  if (!in_place_ && !text_locked().empty()) std::cerr << "progress: " << text_locked() << "\n" << std::flush;
  drawn_ = false;
}

}  // namespace touchcloud::cli
