#include "background_worker.hpp"

namespace touchcloud {

BackgroundWorker::~BackgroundWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void BackgroundWorker::submit(Task task) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    // Tasks never wait for the submitter, so the worker frees room.
    room_.wait(lock, [this] { return queue_.size() < max_queued_; });
    queue_.push_back(std::move(task));
    if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
  }
  wake_.notify_one();
}

void BackgroundWorker::wait_idle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return queue_.empty() && !busy_; });
}

std::exception_ptr BackgroundWorker::error() {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void BackgroundWorker::run() {
  for (;;) {
    Task task;
    std::exception_ptr earlier;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      task = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
      earlier = error_;
    }
    room_.notify_all();  // a task taken, not finished, frees its place
    std::exception_ptr thrown;
    try {
      task(earlier);
    } catch (...) {
      thrown = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (thrown && !error_) error_ = thrown;
      busy_ = false;
    }
    idle_.notify_all();
  }
}

}  // namespace touchcloud
