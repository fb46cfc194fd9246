// Eq. 7 on grids whose overlap can be counted by hand.
#include <gtest/gtest.h>

#include "overlap_filter.hpp"

using namespace touchcloud;
using namespace touchcloud::dedup;

namespace {
// n x n points, `spacing` apart, starting at (x0, 0, 0).
PointCloud grid(int n, float spacing, float x0) {
  PointCloud c;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) c.push_back(pcl::PointXYZ(x0 + i * spacing, j * spacing, 0));
  return c;
}
}  // namespace

TEST(Dedup, FirstTouchIsKeptWholeEvenWhenItsPointsAreClose) {
  OverlapFilter f(1.8);
  EXPECT_EQ(f.add(grid(5, 1.0f, 0))->size(), 25u);  // 1 mm apart, all distinct markers
}

TEST(Dedup, OverlappingPartOfALaterTouchIsDropped) {
  OverlapFilter f(1.8);
  f.add(grid(5, 2.0f, 0));  // x = 0..8
  // Second touch x = 6..14: columns x = 6 and 8 coincide with kept points,
  // x = 10 is 2 mm from the nearest kept point (8) and is kept.
  const CloudPtr added = f.add(grid(5, 2.0f, 6.0f));
  EXPECT_EQ(added->size(), 15u);
  for (const auto& p : added->points) EXPECT_GE(p.x, 10.0f);
  EXPECT_EQ(f.kept().size(), 40u);
}

TEST(Dedup, ThresholdIsStrict) {
  OverlapFilter f(2.0);
  f.add(grid(1, 1, 0));
  PointCloud at, beyond;
  at.push_back(pcl::PointXYZ(2.0f, 0, 0));
  beyond.push_back(pcl::PointXYZ(2.001f, 0, 0));
  EXPECT_EQ(f.add(at)->size(), 0u) << "exactly at the threshold is a duplicate";
  EXPECT_EQ(f.add(beyond)->size(), 1u);
}

TEST(Dedup, DisabledKeepsEverything) {
  OverlapFilter f(1.8);
  f.add_all(grid(3, 1.0f, 0));
  EXPECT_EQ(f.add_all(grid(3, 1.0f, 0))->size(), 9u);
  EXPECT_EQ(f.kept().size(), 18u);
}

// overlap: height. Kept: (0, 0, 5). A new point within 1.8 mm in (x, y) is
// covered at any height above 5 - 1.8 mm (Eq. 7's 3D test keeps one 2 mm
// above); one more than 1.8 mm below it is kept; beyond 1.8 mm in (x, y) it
// is new at any height.
TEST(Dedup, HeightOverlapCoversPointsAboveAKeptOneAndKeepsThoseBelow) {
  PointCloud first;
  first.push_back(pcl::PointXYZ(0, 0, 5));
  const auto one = [](float x, float z) {
    PointCloud c;
    c.push_back(pcl::PointXYZ(x, 0, z));
    return c;
  };
  OverlapFilter height(1.8, OverlapTest::height), distance(1.8);
  height.add(first);
  distance.add(first);
  EXPECT_EQ(height.add(one(1.0f, 7.0f))->size(), 0u) << "2 mm above, 1 mm aside: lifted, covered";
  EXPECT_EQ(distance.add(one(1.0f, 7.0f))->size(), 1u) << "Eq. 7: 2.2 mm away in 3D, new";
  EXPECT_EQ(height.add(one(1.8f, 20.0f))->size(), 0u) << "on the (x, y) threshold, far above";
  EXPECT_EQ(height.add(one(1.0f, 3.2f))->size(), 0u) << "exactly 1.8 mm below: covered";
  EXPECT_EQ(height.add(one(0.5f, 3.1f))->size(), 1u) << "1.9 mm below: better evidence, kept";
  EXPECT_EQ(height.add(one(3.0f, 20.0f))->size(), 1u) << "3 mm aside: a new place";
  EXPECT_EQ(height.kept().size(), 3u);
}
