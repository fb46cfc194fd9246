// The sphere chart around the initial normal: unit normals, the right angle
// from the reference, and its inverse, also far from the camera axis where a
// (z_x, z_y) chart breaks down.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "touchcloud/calibration/normal_chart.hpp"
#include "touchcloud/error.hpp"

using touchcloud::calibration::NormalChart;

TEST(NormalChart, AnglesAreGeodesicAndInvertible) {
  const std::vector<Eigen::Vector3d> references{Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.3, -0.2, 0.93),
                                                Eigen::Vector3d(1, 0, 1e-3)};  // the last: 89.94 deg from z
  const std::vector<Eigen::Vector2d> angles{Eigen::Vector2d(0.1, 0), Eigen::Vector2d(-0.03, 0.04),
                                            Eigen::Vector2d(1e-10, 0), Eigen::Vector2d(1.2, -0.7)};
  for (const auto& n0 : references) {
    const NormalChart chart(n0);
    EXPECT_NEAR((chart.normal(0, 0) - n0.normalized()).norm(), 0, 1e-15);
    for (const auto& ab : angles) {
      const Eigen::Vector3d n = chart.normal(ab.x(), ab.y());
      EXPECT_NEAR(n.norm(), 1, 1e-15);
      // The angle to the reference is |(a, b)|.
      EXPECT_NEAR(std::atan2(n.cross(chart.reference()).norm(), n.dot(chart.reference())), ab.norm(), 1e-14);
      EXPECT_NEAR((chart.coordinates(n) - ab).norm(), 0, 1e-14) << ab.transpose();
    }
  }
}

TEST(NormalChart, ZeroNormalIsRefused) {
  EXPECT_THROW(NormalChart(Eigen::Vector3d::Zero()), touchcloud::InputError);
}
