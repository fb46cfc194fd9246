// The z range of the fitted points beside each lattice node: the points
// within the radius in (x, y), the edge included, and no others.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "near_data.hpp"
#include "touchcloud/error.hpp"

using touchcloud::PointCloud;
using touchcloud::surface_sampler::near_data_range;

namespace {
Eigen::VectorXd axis(double first, double last, int n) { return Eigen::VectorXd::LinSpaced(n, first, last); }
}  // namespace

TEST(NearData, RangeOfThePointsWithinTheRadiusOfEachNode) {
  PointCloud points;
  points.push_back(pcl::PointXYZ(1.0f, 1.0f, 3.0f));
  points.push_back(pcl::PointXYZ(1.5f, 1.0f, -2.0f));
  points.push_back(pcl::PointXYZ(4.0f, 0.0f, 7.0f));
  const auto r = near_data_range(axis(0, 4, 5), axis(0, 2, 3), points, 1.0);
  // Node (1, 1): both first points (0 and 0.5 mm away).
  EXPECT_EQ(r.lo(1, 1), -2.0);
  EXPECT_EQ(r.hi(1, 1), 3.0);
  // Node (2, 1): only the second (0.5 mm; the first is 1 mm away: on the edge, in).
  EXPECT_EQ(r.lo(2, 1), -2.0);
  EXPECT_EQ(r.hi(2, 1), 3.0);
  // Node (1, 0): the first is 1 mm away (in), the second sqrt(1.25) mm (out).
  EXPECT_EQ(r.lo(1, 0), 3.0);
  EXPECT_EQ(r.hi(1, 0), 3.0);
  // Node (3, 2): nothing within 1 mm.
  EXPECT_FALSE(r.has_data(3, 2));
  EXPECT_EQ(r.beyond(3, 2, 100.0), 0.0);
  // Node (4, 0): the third point, on the lattice's corner.
  EXPECT_EQ(r.beyond(4, 0, 7.5), 0.5);
  EXPECT_EQ(r.beyond(4, 0, 6.0), 1.0);
  EXPECT_EQ(r.beyond(4, 0, 7.0), 0.0);
  for (Eigen::Index i = 0; i < r.lo.rows(); ++i)
    for (Eigen::Index j = 0; j < r.lo.cols(); ++j) EXPECT_FALSE(std::isnan(r.lo(i, j)) || std::isnan(r.hi(i, j)));
}

// Points off the lattice (beyond its edges) reach the nodes within the radius only.
TEST(NearData, PointsBeyondTheLatticeReachOnlyNodesWithinTheRadius) {
  PointCloud points;
  points.push_back(pcl::PointXYZ(-0.5f, 0.0f, 1.0f));
  points.push_back(pcl::PointXYZ(50.0f, 50.0f, 1.0f));
  const auto r = near_data_range(axis(0, 4, 5), axis(0, 4, 5), points, 0.6);
  EXPECT_TRUE(r.has_data(0, 0));
  EXPECT_EQ((r.lo.array() <= r.hi.array()).count(), 1);
}

TEST(NearData, ANonFinitePointIsAnError) {
  PointCloud points;
  points.push_back(pcl::PointXYZ(0.0f, 0.0f, 1.0f));
  points.push_back(pcl::PointXYZ(0.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f));
  try {
    near_data_range(axis(0, 4, 5), axis(0, 4, 5), points, 1.0);
    FAIL() << "a NaN point was accepted";
  } catch (const touchcloud::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fitted point 1 has a non-finite coordinate"), std::string::npos) << e.what();
  }
}
