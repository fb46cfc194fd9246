// The checkerboard pressed into the gel: the board lies where the press puts
// it, its corners image through the true rig to pixels that triangulate back
// onto it, only corners pressed into the gel and seen twice are kept, and the
// noise has the asked sigma.
#include <cmath>

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/optics/stereo_triangulation.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/simulation/board/board_press.hpp"

using namespace touchcloud;

namespace {

sensor::GelStereoSensor true_sensor() {
  return sensor::load_gelstereo_sensor(test::source_dir() / "sample_clouds/gelstereo_palm2/sensor_true.yaml");
}

}  // namespace

TEST(BoardPress, CornersFormTheBoardAtThePressDepth) {
  const sensor::Checkerboard board{5, 4, 3.0};
  simulation::BoardPose pose;
  pose.tilt_deg = {20, -10};
  pose.depth_mm = 7;
  pose.spin_deg = 30;
  pose.shift_mm = {1, -1};
  const auto c = simulation::board_corners_sensor(board, pose, 32.5);
  ASSERT_EQ(c.size(), 20u);
  EXPECT_NEAR((c[1] - c[0]).norm(), 3.0, 1e-12);          // along a row
  EXPECT_NEAR((c[5] - c[0]).norm(), 3.0, 1e-12);          // along a column
  EXPECT_NEAR((c[1] - c[0]).dot(c[5] - c[0]), 0, 1e-12);  // square
  const Eigen::Vector3d normal = (c[1] - c[0]).cross(c[5] - c[0]).normalized();
  // A plane 32.5 - 7 mm from the hemisphere's centre, tilted by 20 and 10 deg.
  for (const auto& p : c) EXPECT_NEAR(std::abs(normal.dot(p)), 25.5, 1e-9);
  EXPECT_NEAR(std::abs(normal.z()), std::cos(20 * M_PI / 180) * std::cos(10 * M_PI / 180), 1e-12);
}

TEST(BoardPress, NoiseFreePixelsTriangulateBackOntoTheCorners) {
  const auto truth = true_sensor();
  const auto rig = sensor::make_stereo_rig(truth, true, true);
  const Eigen::Isometry3d left_from_sensor = truth.sensor_from_left_camera().inverse();
  const sensor::Checkerboard board{10, 10, 4.0};  // larger than the pressed disc: some corners drop
  simulation::BoardPose pose;
  pose.tilt_deg = {15, 5};
  pose.depth_mm = 5;
  const auto corners = simulation::board_corners_sensor(board, pose, 32.5);
  std::mt19937_64 rng(1);
  const auto set = simulation::image_press(rig, left_from_sensor, corners, 32.5, {0.0, 0.5}, rng);
  int inside = 0;
  for (const auto& p : corners) inside += p.norm() <= 32.5 && p.z() >= 0.5;
  EXPECT_GT(inside, 10);
  EXPECT_LT(inside, 100);
  EXPECT_EQ(static_cast<int>(set->matches.size()), inside);  // all pressed corners are in view here
  for (const auto& m : set->matches) {
    const Eigen::Vector3d& truth_sensor = corners[static_cast<std::size_t>(m.id)];
    EXPECT_LE(truth_sensor.norm(), 32.5);
    EXPECT_GE(truth_sensor.z(), 0.5);
    const auto point = optics::triangulate_refractive(rig, set->left[static_cast<std::size_t>(m.left)].centre_px,
                                                      set->right[static_cast<std::size_t>(m.right)].centre_px);
    ASSERT_EQ(point.status, optics::TriangulationStatus::Ok);
    EXPECT_LT((point.point_mm - left_from_sensor * truth_sensor).norm(), 1e-6) << m.id;
  }
}

TEST(BoardPress, PixelNoiseHasTheAskedSigma) {
  const auto truth = true_sensor();
  const auto rig = sensor::make_stereo_rig(truth, true, true);
  const Eigen::Isometry3d left_from_sensor = truth.sensor_from_left_camera().inverse();
  const auto corners = simulation::board_corners_sensor({8, 6, 4.0}, {}, 32.5);
  std::mt19937_64 rng(5);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int rep = 0; rep < 50; ++rep) {
    const auto exact = simulation::image_press(rig, left_from_sensor, corners, 32.5, {0.0, 0.5}, rng);
    const auto noisy = simulation::image_press(rig, left_from_sensor, corners, 32.5, {0.3, 0.5}, rng);
    ASSERT_EQ(exact->left.size(), noisy->left.size());
    for (std::size_t i = 0; i < exact->left.size(); ++i)
      for (int k = 0; k < 2; ++k) {
        const double d = noisy->left[i].centre_px[k] - exact->left[i].centre_px[k];
        sum += d, sum2 += d * d, ++n;
      }
  }
  ASSERT_GT(n, 1000);
  EXPECT_NEAR(sum / n, 0, 0.03);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.3, 0.02);
}
