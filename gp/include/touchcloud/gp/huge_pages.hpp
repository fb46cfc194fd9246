// Transparent huge pages for the GP's large buffers. A factor at n = 2,000
// (with room for later touches) is about 45 MB, allocated afresh at every
// refit and written once: with 4 KiB pages that is some 10,000 page faults,
// and on a virtual machine each costs several microseconds (the main job
// spent about a fifth of its main thread in them). Asked for 2 MiB pages, the
// kernel faults 512 times less often. Advice only: where the system keeps
// huge pages off, or on another OS, nothing changes.
#pragma once

#include <cstddef>

#include <Eigen/Core>

namespace touchcloud::gp {

// Advises 2 MiB pages for the whole 2 MiB-aligned pages inside
// [data, data + count) (call before the first write: pages already touched
// stay as they are). Buffers too small to hold one such page are left alone.
// Returns the bytes advised (0 when none or when the kernel refused).
std::size_t advise_huge_pages(double* data, std::size_t count);
// The same for a matrix's storage, just after it was (re)sized.
inline std::size_t advise_huge_pages(Eigen::MatrixXd& m) {
  return advise_huge_pages(m.data(), static_cast<std::size_t>(m.size()));
}

}  // namespace touchcloud::gp
