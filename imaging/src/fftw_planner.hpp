// FFTW's planner is not thread-safe (execution is): every plan is made and
// destroyed under this one lock.
#pragma once

#include <mutex>

namespace touchcloud::imaging {

inline std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace touchcloud::imaging
