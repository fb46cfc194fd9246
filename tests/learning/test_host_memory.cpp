// keep_freed_memory_for_reuse: an activation libtorch frees stays in the
// heap for the next pass instead of being unmapped or trimmed (and faulted
// in again page by page). Each ctest entry is a fresh process, so glibc's
// adaptive thresholds start from their defaults here.
#include <gtest/gtest.h>

#include <malloc.h>

#include <torch/torch.h>

#include "touchcloud/learning/host_memory.hpp"

namespace {

TEST(HostMemory, AFreedActivationStaysInTheHeapForTheNextPass) {
  touchcloud::learning::keep_freed_memory_for_reuse();
  constexpr std::size_t kBytes = 24u << 20;  // a 256 x 256 cost volume is about 7 MB; a batch more
  const std::size_t mapped_before = mallinfo2().hblkhd;
  {
    const torch::Tensor activation = torch::ones({static_cast<std::int64_t>(kBytes / sizeof(float))});
    ASSERT_EQ(activation.sum().item<double>(), static_cast<double>(kBytes / sizeof(float)));
    // From the heap, not a block of its own (glibc's default for > 128 KiB).
    EXPECT_LT(mallinfo2().hblkhd - mapped_before, kBytes) << "the activation was mmapped";
  }
  // Freed, it is kept (not trimmed) for the next allocation.
  EXPECT_GE(mallinfo2().fordblks, kBytes) << "the freed activation was returned to the system";
}

}  // namespace
