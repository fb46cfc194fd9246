#include "touchcloud/learning/host_memory.hpp"

#include <malloc.h>

namespace touchcloud::learning {

void keep_freed_memory_for_reuse() {
  // 32 MiB is the largest mmap threshold glibc accepts on 64-bit systems;
  // setting either value turns off glibc's own adaptive thresholds, so both
  // are set (the trim threshold alone made every block above 128 KiB an mmap).
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
}

}  // namespace touchcloud::learning
