// Columns of a lower triangle over two threads: every column once, the
// entries split about evenly, the first part on another thread.
#include <gtest/gtest.h>

#include <mutex>
#include <thread>
#include <vector>

#include "touchcloud/gp/triangle_columns.hpp"

namespace touchcloud::gp {
namespace {

TEST(TriangleColumns, EachColumnOnceWithHalfTheEntriesEachSide) {
  for (Eigen::Index n : {0, 1, 255, 256, 1000, 4097}) {
    std::vector<int> seen(static_cast<std::size_t>(n), 0);
    std::mutex mutex;
    std::vector<std::pair<Eigen::Index, std::thread::id>> parts;  // (entries, thread)
    for_triangle_columns(n, [&](Eigen::Index first, Eigen::Index last) {
      Eigen::Index entries = 0;
      for (Eigen::Index j = first; j < last; ++j) ++seen[static_cast<std::size_t>(j)], entries += n - j;
      std::lock_guard<std::mutex> lock(mutex);
      parts.emplace_back(entries, std::this_thread::get_id());
    });
    for (Eigen::Index j = 0; j < n; ++j) ASSERT_EQ(seen[static_cast<std::size_t>(j)], 1) << "n " << n << ", column " << j;
    if (n * (n + 1) / 2 < kTwoThreadWork) {  // n < 256
      ASSERT_EQ(parts.size(), 1u) << n;
      EXPECT_EQ(parts[0].second, std::this_thread::get_id());
      continue;
    }
    ASSERT_EQ(parts.size(), 2u) << n;
    EXPECT_NE(parts[0].second, parts[1].second) << n;
    const double total = 0.5 * static_cast<double>(n) * static_cast<double>(n + 1);
    for (const auto& part : parts) EXPECT_NEAR(static_cast<double>(part.first) / total, 0.5, 0.01) << n;
  }
}

}  // namespace
}  // namespace touchcloud::gp
