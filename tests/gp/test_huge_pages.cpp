// Huge-page advice for the GP's large buffers: only whole 2 MiB pages inside
// the buffer are advised, small buffers are left alone, and where the system
// grants huge pages on request a touched buffer is backed by them.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include <Eigen/Core>

#include "touchcloud/gp/huge_pages.hpp"

namespace touchcloud::gp {
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

// "always", "madvise", "never", or "" where the kernel has no such setting.
std::string transparent_huge_pages() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string word;
  while (in >> word)
    if (word.size() > 2 && word.front() == '[') return word.substr(1, word.size() - 2);
  return "";
}

// kB of huge pages backing the mapping that holds `address`, from /proc/self/smaps.
long anon_huge_kb_at(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= a && a < hi;
      continue;
    }
    long kb = 0;
    if (inside && line.rfind("AnonHugePages:", 0) == 0 && std::istringstream(line.substr(14)) >> kb) return kb;
  }
  return -1;
}

TEST(GpHugePages, AdvisesOnlyWholeAlignedPagesInside) {
  Eigen::MatrixXd a(1200, 1200);  // 11 MB: at least four whole 2 MiB pages inside
  const std::size_t bytes = advise_huge_pages(a);
  if (transparent_huge_pages().empty()) GTEST_SKIP() << "no transparent huge pages on this system";
  EXPECT_EQ(bytes % kHugePage, 0u);
  EXPECT_GE(bytes, 4 * kHugePage);
  EXPECT_LE(bytes, static_cast<std::size_t>(a.size()) * sizeof(double));
}

TEST(GpHugePages, LeavesBuffersWithoutAWholePageAlone) {
  Eigen::VectorXd small(1000);
  EXPECT_EQ(advise_huge_pages(small.data(), static_cast<std::size_t>(small.size())), 0u);
  EXPECT_EQ(advise_huge_pages(nullptr, 1 << 22), 0u);
  EXPECT_EQ(advise_huge_pages(small.data(), 0), 0u);
}

TEST(GpHugePages, ATouchedAdvisedBufferIsBackedByHugePages) {
  const std::string mode = transparent_huge_pages();
  if (mode != "always" && mode != "madvise") GTEST_SKIP() << "transparent huge pages are '" << mode << "' here";
  Eigen::MatrixXd a(2000, 2000);  // 32 MB, as a GP factor at n = 2,000
  ASSERT_GT(advise_huge_pages(a), 0u);
  a.setZero();
  EXPECT_GE(anon_huge_kb_at(a.data() + a.size() / 2), 2048) << "THP mode " << mode;
}

}  // namespace
}  // namespace touchcloud::gp
