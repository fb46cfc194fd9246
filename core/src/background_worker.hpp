// One thread that runs a pipeline's background stages, call after call in
// the order they were submitted. Private to the core.
//
// FIFO order on a single thread is what keeps background stages simple: a
// call's inputs from other background stages were computed by calls
// submitted before it, so they are ready when it starts, and a stage's calls
// never overlap one another.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace touchcloud {

class BackgroundWorker {
 public:
  // A task gets the first error of an earlier task (null if none): it then
  // only passes that error on to whoever waits for its results.
  using Task = std::function<void(std::exception_ptr earlier_error)>;

  // submit() waits while `max_queued` tasks wait to start, so a slow
  // background stage holds the inputs of at most that many calls.
  explicit BackgroundWorker(std::size_t max_queued = 16) : max_queued_(max_queued < 1 ? 1 : max_queued) {}
  BackgroundWorker(const BackgroundWorker&) = delete;
  BackgroundWorker& operator=(const BackgroundWorker&) = delete;
  // Drops the tasks not started and waits for the running one.
  ~BackgroundWorker();

  // Queues `task`; the thread starts with the first one.
  void submit(Task task);
  // Waits until every submitted task has run.
  void wait_idle();
  // The first exception a task threw, or null.
  std::exception_ptr error();

 private:
  void run();

  const std::size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable wake_, room_, idle_;  // a task queued; one taken; none left
  std::deque<Task> queue_;
  bool busy_ = false, stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: started after, and joined before, the rest is gone
};

}  // namespace touchcloud
