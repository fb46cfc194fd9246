// Subsets of runs of consecutive points for hyperparameter selection.
#include <gtest/gtest.h>

#include <set>

#include "touchcloud/gp/point_subset.hpp"

namespace touchcloud::gp {
namespace {

// Points numbered by their row: x = row, so a subset shows which rows it took.
std::pair<Eigen::MatrixX2d, Eigen::VectorXd> numbered(Eigen::Index n) {
  Eigen::MatrixX2d xy(n, 2);
  xy.col(0) = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1));
  xy.col(1).setZero();
  return {xy, -xy.col(0)};
}

TEST(GpPointSubset, AllPointsWhenTheSubsetIsNotSmaller) {
  const auto [xy, z] = numbered(40);
  const auto [sub_xy, sub_z] = subset_of_runs(xy, z, 50, 16);
  EXPECT_EQ(sub_xy, xy);
  EXPECT_EQ(sub_z, z);
}

// Runs of consecutive rows, in order, none overlapping (9 of 10 rows in 6
// runs is where an even spacing of run starts alone would overlap), the
// first starting at row 0.
TEST(GpPointSubset, RunsAreConsecutiveDisjointAndSpread) {
  for (const auto& [n, size, runs] : {std::tuple{10, 9, 6}, std::tuple{2000, 1000, 16}, std::tuple{1001, 500, 7}}) {
    const auto [xy, z] = numbered(n);
    const auto [sub_xy, sub_z] = subset_of_runs(xy, z, size, runs);
    ASSERT_EQ(sub_xy.rows(), size);
    EXPECT_EQ(sub_z, -sub_xy.col(0));
    std::set<double> rows(sub_xy.col(0).data(), sub_xy.col(0).data() + size);
    EXPECT_EQ(static_cast<Eigen::Index>(rows.size()), size) << "overlapping runs, n = " << n;
    int breaks = 0;
    for (Eigen::Index i = 1; i < size; ++i) {
      EXPECT_GT(sub_xy(i, 0), sub_xy(i - 1, 0));
      breaks += sub_xy(i, 0) != sub_xy(i - 1, 0) + 1;
    }
    EXPECT_LE(breaks, runs - 1);
    EXPECT_EQ(sub_xy(0, 0), 0.0);
    EXPECT_GE(sub_xy(size - 1, 0), static_cast<double>(n - n / runs - 1)) << "the last run sits in the last stretch";
  }
}

}  // namespace
}  // namespace touchcloud::gp
