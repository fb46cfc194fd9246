// The pinhole + Brown-Conrady camera against OpenCV's own implementation.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "optics_fixture.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/optics/pinhole_camera.hpp"

namespace touchcloud::optics {
namespace {

cv::Matx33d camera_matrix(const CameraIntrinsics& k) {
  return {k.fx_px, 0, k.cx_px, 0, k.fy_px, k.cy_px, 0, 0, 1};
}
cv::Vec<double, 5> distortion_vector(const CameraIntrinsics& k) {
  const BrownConrady& d = k.distortion;
  return {d.k1, d.k2, d.p1, d.p2, d.k3};
}

TEST(PinholeCamera, DefaultsAreThePalm2SimulatorCamera) {
  const CameraIntrinsics k = PinholeCamera().intrinsics();
  EXPECT_EQ(k.width_px, 1280);
  EXPECT_EQ(k.height_px, 720);
  EXPECT_EQ(k.fx_px, 651.5);
  EXPECT_EQ(k.fy_px, 652.0);
  EXPECT_EQ(k.cx_px, 598.6);
  EXPECT_EQ(k.cy_px, 377.1);
}

TEST(PinholeCamera, ProjectMatchesOpenCvProjectPoints) {
  for (const CameraIntrinsics& k : {test::left_intrinsics(), test::right_intrinsics()}) {
    const PinholeCamera camera(k);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> lateral(-0.7, 0.7), depth(5.0, 120.0);
    std::vector<cv::Point3d> points;
    for (int i = 0; i < 1000; ++i) {
      const double z = depth(rng);
      points.emplace_back(lateral(rng) * z, 0.5 * lateral(rng) * z, z);
    }
    std::vector<cv::Point2d> expected;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix(k), distortion_vector(k),
                      expected);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const PixelProjection got = camera.project({points[i].x, points[i].y, points[i].z});
      ASSERT_TRUE(got.status == TraceStatus::Ok || got.status == TraceStatus::OutOfView);
      EXPECT_NEAR(got.pixel_px.x(), expected[i].x, 1e-9);
      EXPECT_NEAR(got.pixel_px.y(), expected[i].y, 1e-9);
    }
  }
}

TEST(PinholeCamera, BackProjectMatchesOpenCvUndistortPoints) {
  for (const CameraIntrinsics& k : {test::left_intrinsics(), test::right_intrinsics()}) {
    const PinholeCamera camera(k);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, k.width_px - 1.0), v(0.0, k.height_px - 1.0);
    std::vector<cv::Point2d> pixels;
    for (int i = 0; i < 1000; ++i) pixels.emplace_back(u(rng), v(rng));
    pixels.emplace_back(0, 0);  // the far corners, where distortion is strongest
    pixels.emplace_back(k.width_px - 1.0, k.height_px - 1.0);
    // OpenCV's default stops after 5 fixed-point steps; run it to convergence.
    std::vector<cv::Point2d> expected;
    cv::undistortPoints(pixels, expected, camera_matrix(k), distortion_vector(k), cv::noArray(), cv::noArray(),
                        cv::TermCriteria(cv::TermCriteria::COUNT, 500, 0));
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      const PixelDirection got = camera.back_project({pixels[i].x, pixels[i].y});
      ASSERT_EQ(got.status, TraceStatus::Ok);
      EXPECT_NEAR(got.direction.norm(), 1.0, 1e-15);
      EXPECT_NEAR(got.direction.x() / got.direction.z(), expected[i].x, 1e-9);
      EXPECT_NEAR(got.direction.y() / got.direction.z(), expected[i].y, 1e-9);
    }
  }
}

TEST(PinholeCamera, BackProjectThenProjectReturnsThePixel) {
  const PinholeCamera camera(test::left_intrinsics());
  for (double u = 0; u < 1280; u += 63.7) {
    for (double v = 0; v < 720; v += 41.3) {
      const PixelDirection ray = camera.back_project({u, v});
      ASSERT_EQ(ray.status, TraceStatus::Ok);
      const PixelProjection pixel = camera.project(37.0 * ray.direction);
      ASSERT_EQ(pixel.status, TraceStatus::Ok);
      EXPECT_NEAR((pixel.pixel_px - Eigen::Vector2d(u, v)).norm(), 0.0, 1e-9);
    }
  }
}

TEST(PinholeCamera, ReportsPointsItCannotImage) {
  const PinholeCamera camera(test::left_intrinsics());
  EXPECT_EQ(camera.project({0, 0, -1}).status, TraceStatus::BehindCamera);
  EXPECT_EQ(camera.project({1, 0, 0}).status, TraceStatus::BehindCamera);

  // Off the image but on the lens model's monotonic part: pixel still given.
  const PixelProjection off = camera.project({1.2, 0, 1});
  EXPECT_EQ(off.status, TraceStatus::OutOfView);
  EXPECT_GT(off.pixel_px.x(), 1280);
  EXPECT_TRUE(off.pixel_px.allFinite());

  // The test lens folds back near r^2 = 3.3 (1 - 0.36u + 0.25u^2 - 0.07u^3 = 0);
  // a point past the fold would land inside the image if projected naively.
  EXPECT_NEAR(camera.fold_radius2(), 3.3, 0.1);
  const Eigen::Vector2d naive = camera.distort({2.25, 0.0});
  EXPECT_TRUE(camera.in_view({651.5 * naive.x() + 598.6, 377.1}));
  EXPECT_EQ(camera.project({2.25, 0, 1}).status, TraceStatus::OutOfView);

  EXPECT_TRUE(camera.in_view({-0.5, -0.5}));
  EXPECT_TRUE(camera.in_view({1279.4, 719.4}));
  EXPECT_FALSE(camera.in_view({1279.5, 100}));
  EXPECT_FALSE(camera.in_view({100, -0.51}));

  // Far off the image, beyond the fold: the lens model cannot be inverted.
  EXPECT_EQ(camera.back_project({1e6, 0}).status, TraceStatus::UndistortionFailed);
  EXPECT_EQ(PinholeCamera().fold_radius2(), std::numeric_limits<double>::infinity());
}

TEST(PinholeCamera, RejectsInvalidIntrinsicsNamingTheField) {
  CameraIntrinsics k;
  k.fx_px = 0;
  k.height_px = -3;
  k.distortion.p2 = std::nan("");
  try {
    PinholeCamera camera(k);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("camera.fx_px = 0: must be finite and > 0"), std::string::npos) << what;
    EXPECT_NE(what.find("camera.height_px = -3"), std::string::npos) << what;
    EXPECT_NE(what.find("camera.distortion.p2"), std::string::npos) << what;
    EXPECT_EQ(e.diagnostics().size(), 3u);
  }
}

}  // namespace
}  // namespace touchcloud::optics
