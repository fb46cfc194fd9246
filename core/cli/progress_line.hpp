// Progress of a long batch (sweep runs, scored estimates) on stderr: done /
// total, rate and time left on one line redrawn in place when stderr is a
// terminal; quiet in logs and CI unless asked for (--progress), and then one
// plain line every few seconds and one at the end instead of redraws.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace touchcloud::cli {

// "3/10 runs, 0.5 runs/s, about 14 s left" (the rate and time left once
// something is done): `done` of `total` after `elapsed_s`, of which
// `done_at_start` were done when the clock started (a count that began
// part way, such as a resumed training run).
std::string progress_text(std::size_t done, std::size_t total, double elapsed_s, const std::string& noun,
                          std::size_t done_at_start = 0);

class ProgressLine {
 public:
  // `noun`: what is counted ("runs"); `forced`: also when stderr is not a
  // terminal; not `enabled` (an MPI rank other than 0): never drawn.
  ProgressLine(std::size_t total, std::string noun, bool forced, bool enabled = true);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  void stage(const std::string& what);  // shown after the count ("loading ground truth X")
  void done_one();
  // Where the batch stands, when it counts for itself (a run's loop).
  void set(std::size_t done, std::size_t total, const std::string& noun);
  // Where one long step of it stands (a stage's epochs), shown after the
  // batch's count with its own rate, from its first report on, until the
  // batch's count moves or another step reports.
  void set_step(const std::string& step, std::size_t done, std::size_t total, const std::string& noun);
  // A line of the batch's own log, printed above the progress line.
  void print_above(const std::string& line);
  // Stops drawing and clears the line (before the results are printed).
  void finish();

 private:
  void tick();
  std::string text_locked() const;

  using Clock = std::chrono::steady_clock;
  struct Step {
    std::string name, noun;
    std::size_t done = 0, total = 0, done_at_start = 0;
    Clock::time_point start;
  };
  std::mutex mutex_;
  std::condition_variable wake_;
  std::size_t total_, done_ = 0;
  std::string noun_, what_;
  std::optional<Step> step_;
  bool in_place_ = false, drawn_ = false, stopped_ = false;
  Clock::time_point start_ = Clock::now();
  std::thread ticker_;
};

}  // namespace touchcloud::cli
