// The end of a thread that works for a waiting consumer (a camera's capture
// thread, a stream run for Python): what its work throws is kept for the
// consumer to rethrow, and the end is marked under the consumer's mutex, so
// that a wait for "a result or the end" never misses it.
#pragma once

#include <condition_variable>
#include <exception>
#include <mutex>

namespace touchcloud {

// Runs `work`; keeps what it throws in `error`; then sets `ended` and wakes
// every waiter on `changed`. `work` locks `mutex` itself where it shares state.
template <class Work>
void run_to_end(Work&& work, std::mutex& mutex, std::condition_variable& changed, std::exception_ptr& error,
                bool& ended) {
  try {
    work();
  } catch (...) {
    std::lock_guard lock(mutex);
    error = std::current_exception();
  }
  {
    std::lock_guard lock(mutex);
    ended = true;
  }
  changed.notify_all();
}

}  // namespace touchcloud
