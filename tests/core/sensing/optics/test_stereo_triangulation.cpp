// Triangulating silicone rays (RSRT) and plain rays (refraction.md hard cases
// 1, 2, 9, 10): agreement with OpenCV's DLT where it applies, nearly parallel
// rays, left/right symmetry, pixel noise, and what ignoring refraction costs.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "optics_fixture.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/optics/stereo_triangulation.hpp"

namespace touchcloud::optics {
namespace {

// Normalised undistorted coordinates by OpenCV, run to convergence.
cv::Mat opencv_normalised(const PinholeCamera& camera, const std::vector<Eigen::Vector2d>& pixels) {
  const CameraIntrinsics& k = camera.intrinsics();
  std::vector<cv::Point2d> in, out;
  for (const Eigen::Vector2d& p : pixels) in.emplace_back(p.x(), p.y());
  cv::undistortPoints(in, out, cv::Matx33d(k.fx_px, 0, k.cx_px, 0, k.fy_px, k.cy_px, 0, 0, 1),
                      cv::Vec<double, 5>(k.distortion.k1, k.distortion.k2, k.distortion.p1, k.distortion.p2,
                                         k.distortion.k3),
                      cv::noArray(), cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT, 500, 0));
  cv::Mat rows(2, static_cast<int>(out.size()), CV_64F);
  for (int i = 0; i < rows.cols; ++i) {
    rows.at<double>(0, i) = out[i].x;
    rows.at<double>(1, i) = out[i].y;
  }
  return rows;
}

// Hard case 1: with equal indices RSRT is ordinary stereo triangulation.
TEST(StereoTriangulation, EqualIndicesMatchOpenCvTriangulatePoints) {
  test::RigSetup setup;
  setup.tilt_deg = 5;
  setup.azimuth_deg = 300;
  setup.mu_air = setup.mu_acrylic = setup.mu_silicone = 1.3;
  const StereoRig rig = test::make_rig(setup);
  const test::StereoView view = test::visible_in_both(rig, test::dome_points(rig, 500, 31));
  ASSERT_GT(view.points_mm.size(), 300u);

  const cv::Mat left = opencv_normalised(rig.camera(StereoSide::Left), view.left_px);
  const cv::Mat right = opencv_normalised(rig.camera(StereoSide::Right), view.right_px);
  cv::Matx34d left_projection = cv::Matx34d::eye(), right_projection;
  const Eigen::Matrix<double, 3, 4> right_pose = rig.right_from_left().matrix().topRows<3>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) right_projection(r, c) = right_pose(r, c);
  cv::Mat homogeneous;
  cv::triangulatePoints(left_projection, right_projection, left, right, homogeneous);

  double worst_opencv_mm = 0, worst_pinhole_mm = 0, worst_truth_mm = 0;
  for (std::size_t i = 0; i < view.points_mm.size(); ++i) {
    const TriangulatedPoint rsrt = triangulate_refractive(rig, view.left_px[i], view.right_px[i]);
    ASSERT_EQ(rsrt.status, TriangulationStatus::Ok);
    const int col = static_cast<int>(i);
    const double w = homogeneous.at<double>(3, col);
    const Eigen::Vector3d dlt(homogeneous.at<double>(0, col) / w, homogeneous.at<double>(1, col) / w,
                              homogeneous.at<double>(2, col) / w);
    const TriangulatedPoint pinhole = triangulate_pinhole(rig, view.left_px[i], view.right_px[i]);
    ASSERT_EQ(pinhole.status, TriangulationStatus::Ok);
    worst_opencv_mm = std::max(worst_opencv_mm, (rsrt.point_mm - dlt).norm());
    worst_pinhole_mm = std::max(worst_pinhole_mm, (rsrt.point_mm - pinhole.point_mm).norm());
    worst_truth_mm = std::max(worst_truth_mm, (rsrt.point_mm - view.points_mm[i]).norm());
  }
  EXPECT_LE(worst_opencv_mm, 1e-9);
  EXPECT_LE(worst_pinhole_mm, 1e-9);
  EXPECT_LE(worst_truth_mm, 1e-9);
}

// Hard case 2, for points.
TEST(StereoTriangulation, ScalingAllIndicesGivesTheSamePoints) {
  test::RigSetup setup;
  setup.tilt_deg = 8;
  setup.azimuth_deg = 20;
  const StereoRig rig = test::make_rig(setup);
  test::RigSetup scaled_setup = setup;
  scaled_setup.mu_air *= 2.3;
  scaled_setup.mu_acrylic *= 2.3;
  scaled_setup.mu_silicone *= 2.3;
  const StereoRig scaled = test::make_rig(scaled_setup);
  const test::StereoView view = test::visible_in_both(rig, test::dome_points(rig, 500, 37));
  ASSERT_GT(view.points_mm.size(), 300u);
  double worst_mm = 0;
  for (std::size_t i = 0; i < view.points_mm.size(); ++i) {
    const TriangulatedPoint a = triangulate_refractive(rig, view.left_px[i], view.right_px[i]);
    const TriangulatedPoint b = triangulate_refractive(scaled, view.left_px[i], view.right_px[i]);
    ASSERT_EQ(a.status, TriangulationStatus::Ok);
    ASSERT_EQ(b.status, TriangulationStatus::Ok);
    worst_mm = std::max(worst_mm, (a.point_mm - b.point_mm).norm());
  }
  EXPECT_LE(worst_mm, 1e-12);
}

TEST(StereoTriangulation, NoiseFreePixelsGiveTheMarkerBack) {
  test::RigSetup setup;
  setup.tilt_deg = 10;
  setup.azimuth_deg = 160;
  const StereoRig rig = test::make_rig(setup);
  const test::StereoView view = test::visible_in_both(rig, test::dome_points(rig, 2000, 41));
  ASSERT_GT(view.points_mm.size(), 1200u);
  double worst_mm = 0, worst_gap_mm = 0;
  for (std::size_t i = 0; i < view.points_mm.size(); ++i) {
    const TriangulatedPoint p = triangulate_refractive(rig, view.left_px[i], view.right_px[i]);
    ASSERT_EQ(p.status, TriangulationStatus::Ok);
    worst_mm = std::max(worst_mm, (p.point_mm - view.points_mm[i]).norm());
    worst_gap_mm = std::max(worst_gap_mm, p.gap_mm);
  }
  EXPECT_LE(worst_mm, 1e-9);
  EXPECT_LE(worst_gap_mm, 1e-9);

  // A marker on the gel face itself: s = 0 up to rounding is not "behind".
  const Eigen::Vector3d n = rig.plate().normal;
  const Eigen::Vector3d on_face = (rig.plate().gel_face_mm() - n.dot(Eigen::Vector3d(10, 2, 0))) * n +
                                  Eigen::Vector3d(10, 2, 0);
  const RefractedPixel left = project_refracted(rig, StereoSide::Left, on_face);
  const RefractedPixel right = project_refracted(rig, StereoSide::Right, on_face);
  ASSERT_EQ(left.status, TraceStatus::Ok);
  ASSERT_EQ(right.status, TraceStatus::Ok);
  const TriangulatedPoint face = triangulate_refractive(rig, left.pixel_px, right.pixel_px);
  EXPECT_EQ(face.status, TriangulationStatus::Ok);
  EXPECT_NEAR((face.point_mm - on_face).norm(), 0.0, 1e-9);
}

// Hard case 9: the cross-product form holds its digits as the rays turn parallel.
TEST(StereoTriangulation, NearlyParallelRaysAreDegenerateBelowTheThreshold) {
  const RayTriangulationOptions options;  // min_ray_angle_rad = 1e-6
  std::mt19937 rng(43);
  std::normal_distribution<double> normal(0.0, 1.0);
  int ok = 0, degenerate = 0;
  for (int half_decade = 0; half_decade <= 14; ++half_decade) {
    const double angle = std::pow(10.0, -2.0 - 0.5 * half_decade);
    for (int trial = 0; trial < 20; ++trial) {
      // Two rays that truly meet at the marker, from origins 35 and 80 mm back
      // (|w| ~ 45 mm, as far apart as the gel's depth range).
      const Eigen::Vector3d marker(10 * normal(rng), 10 * normal(rng), 60 + 5 * normal(rng));
      const Eigen::Vector3d base = Eigen::Vector3d(0.3 * normal(rng), 0.3 * normal(rng), 1.0).normalized();
      const Eigen::Vector3d across = base.cross(Eigen::Vector3d(normal(rng), normal(rng), normal(rng))).normalized();
      const Eigen::Vector3d d_left = base;
      const Eigen::Vector3d d_right = (std::cos(angle) * base + std::sin(angle) * across).normalized();
      const Eigen::Vector3d o_left = marker - 35.0 * d_left, o_right = marker - 80.0 * d_right;
      const TriangulatedPoint p = triangulate_rays(o_left, d_left, o_right, d_right, options);
      ASSERT_TRUE(p.point_mm.allFinite() && std::isfinite(p.gap_mm) && std::isfinite(p.s_left_mm) &&
                  std::isfinite(p.s_right_mm));
      if (angle > 1.01 * options.min_ray_angle_rad) {
        ASSERT_EQ(p.status, TriangulationStatus::Ok) << angle;
        EXPECT_LE(p.gap_mm, 1e-12) << angle;
        // Along the rays the point is only known to (rounding / angle).
        EXPECT_LE((p.point_mm - marker).norm(), 1e-12 + 1e-13 / angle) << angle;
        EXPECT_NEAR(p.s_left_mm, 35.0, 1e-12 + 1e-13 / angle) << angle;
        EXPECT_NEAR(p.s_right_mm, 80.0, 1e-12 + 1e-13 / angle) << angle;
        ++ok;
      } else if (angle < 0.99 * options.min_ray_angle_rad) {
        EXPECT_EQ(p.status, TriangulationStatus::Degenerate) << angle;
        EXPECT_NEAR(p.gap_mm, (o_right - o_left).cross(d_left).norm(), 1e-12);
        ++degenerate;
      }
    }
  }
  EXPECT_EQ(ok, 20 * 8);          // 1e-2 .. 1.6e-6
  EXPECT_EQ(degenerate, 20 * 6);  // 3.2e-7 .. 1e-9
  // Exactly parallel, and a zero direction.
  const Eigen::Vector3d base = Eigen::Vector3d(0.1, -0.05, 1.0).normalized();
  const TriangulatedPoint parallel = triangulate_rays({0, 0, 0}, base, {1, 0, 0}, base, options);
  EXPECT_EQ(parallel.status, TriangulationStatus::Degenerate);
  EXPECT_NEAR(parallel.gap_mm, base.cross(Eigen::Vector3d::UnitX()).norm(), 1e-15);
  EXPECT_EQ(triangulate_rays({0, 0, 0}, {0, 0, 0}, {1, 0, 0}, base).status, TriangulationStatus::Degenerate);

  // Rays that meet at ordinary angles: zero gap, the meeting point.
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d point(normal(rng) * 20, normal(rng) * 20, 50 + normal(rng) * 10);
    const Eigen::Vector3d a = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Eigen::Vector3d b = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const TriangulatedPoint p = triangulate_rays(point - 30.0 * a, a, point - 25.0 * b, b);
    if (a.cross(b).norm() < 1e-2) continue;
    ASSERT_EQ(p.status, TriangulationStatus::Ok);
    EXPECT_LE(p.gap_mm, 1e-12);
    EXPECT_LE((p.point_mm - point).norm(), 1e-11);
  }
}

TEST(StereoTriangulation, RaysMeetingBehindAnOriginAreFlagged) {
  const Eigen::Vector3d meet(0, 0, 20);
  const Eigen::Vector3d a = Eigen::Vector3d(0.2, 0, 1).normalized(), b = Eigen::Vector3d(-0.2, 0.1, 1).normalized();
  const TriangulatedPoint behind = triangulate_rays(meet + 5.0 * a, a, meet - 5.0 * b, b);
  EXPECT_EQ(behind.status, TriangulationStatus::BehindRayOrigin);
  EXPECT_NEAR(behind.s_left_mm, -5.0, 1e-12);
  EXPECT_NEAR(behind.s_right_mm, 5.0, 1e-12);
  EXPECT_NEAR((behind.point_mm - meet).norm(), 0.0, 1e-12);
  // Within the tolerance of the origin it is accepted.
  EXPECT_EQ(triangulate_rays(meet + 1e-12 * a, a, meet - 5.0 * b, b).status, TriangulationStatus::Ok);

  EXPECT_THROW(triangulate_rays(meet, Eigen::Vector3d(std::nan(""), 0, 1), meet, b), InputError);

  RayTriangulationOptions bad;
  bad.min_ray_angle_rad = 0;
  try {
    triangulate_rays(meet, a, meet, b, bad);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangulation.min_ray_angle_rad = 0"), std::string::npos) << e.what();
  }
}

// Hard case 10a: which camera is called "left" does not matter.
TEST(StereoTriangulation, SwappingLeftAndRightGivesTheSamePoint) {
  test::RigSetup setup;
  setup.tilt_deg = 6;
  setup.azimuth_deg = 210;
  const StereoRig rig = test::make_rig(setup);
  const StereoRig swapped = rig.swapped();
  const Eigen::Isometry3d left_from_right = rig.right_from_left().inverse();
  const test::StereoView view = test::visible_in_both(rig, test::dome_points(rig, 1000, 47));
  ASSERT_GT(view.points_mm.size(), 600u);
  std::mt19937 rng(53);
  std::normal_distribution<double> noise(0.0, 0.3);
  double worst_mm = 0;
  for (std::size_t i = 0; i < view.points_mm.size(); ++i) {
    const Eigen::Vector2d left_px = view.left_px[i] + Eigen::Vector2d(noise(rng), noise(rng));
    const Eigen::Vector2d right_px = view.right_px[i] + Eigen::Vector2d(noise(rng), noise(rng));
    const TriangulatedPoint p = triangulate_refractive(rig, left_px, right_px);
    const TriangulatedPoint q = triangulate_refractive(swapped, right_px, left_px);
    ASSERT_EQ(p.status, TriangulationStatus::Ok);
    ASSERT_EQ(q.status, TriangulationStatus::Ok);
    EXPECT_NEAR(p.gap_mm, q.gap_mm, 1e-9);
    worst_mm = std::max(worst_mm, (p.point_mm - left_from_right * q.point_mm).norm());
  }
  EXPECT_LE(worst_mm, 1e-9);
}

struct ErrorStats {
  Eigen::Vector3d rms_mm = Eigen::Vector3d::Zero();  // per axis of the left camera frame
  double rms_total_mm = 0, max_mm = 0;
  int count = 0;
};

ErrorStats triangulation_errors(const StereoRig& rig, const test::StereoView& view, double noise_px, bool refractive) {
  std::mt19937 rng(59);  // the same draws for every noise level
  std::normal_distribution<double> unit_noise(0.0, 1.0);
  ErrorStats stats;
  for (std::size_t i = 0; i < view.points_mm.size(); ++i) {
    const Eigen::Vector2d dl(unit_noise(rng), unit_noise(rng)), dr(unit_noise(rng), unit_noise(rng));
    const Eigen::Vector2d left_px = view.left_px[i] + noise_px * dl, right_px = view.right_px[i] + noise_px * dr;
    const TriangulatedPoint p = refractive ? triangulate_refractive(rig, left_px, right_px)
                                           : triangulate_pinhole(rig, left_px, right_px);
    if (p.status != TriangulationStatus::Ok) continue;  // a noisy pixel pushed off the image
    const Eigen::Vector3d error = p.point_mm - view.points_mm[i];
    stats.rms_mm += error.cwiseAbs2();
    stats.max_mm = std::max(stats.max_mm, error.norm());
    ++stats.count;
  }
  stats.rms_mm = (stats.rms_mm / stats.count).cwiseSqrt();
  stats.rms_total_mm = stats.rms_mm.norm();
  return stats;
}

std::string describe(const ErrorStats& s) {
  return "rms x " + std::to_string(s.rms_mm.x()) + " y " + std::to_string(s.rms_mm.y()) + " z " +
         std::to_string(s.rms_mm.z()) + " total " + std::to_string(s.rms_total_mm) + " max " +
         std::to_string(s.max_mm) + " mm over " + std::to_string(s.count) + " markers";
}

// Hard case 10b: pixel noise propagates linearly, mostly into depth; ignoring
// the plate costs millimetres.
TEST(StereoTriangulation, NoiseScalesLinearlyAndIgnoringRefractionCostsMillimetres) {
  test::RigSetup setup;
  setup.tilt_deg = 5;
  setup.azimuth_deg = 45;
  const StereoRig rig = test::make_rig(setup);
  const test::StereoView view = test::visible_in_both(rig, test::dome_points(rig, 3000, 61));
  ASSERT_GT(view.points_mm.size(), 2000u);

  const ErrorStats low = triangulation_errors(rig, view, 0.1, true);
  const ErrorStats high = triangulation_errors(rig, view, 0.3, true);
  const ErrorStats pinhole = triangulation_errors(rig, view, 0.0, false);
  std::cout << "[ RSRT 0.1 px ] " << describe(low) << "\n"
            << "[ RSRT 0.3 px ] " << describe(high) << "\n"
            << "[ pinhole, no noise ] " << describe(pinhole) << "\n";
  RecordProperty("rsrt_0.1px_rms_mm", describe(low));
  RecordProperty("rsrt_0.3px_rms_mm", describe(high));
  RecordProperty("pinhole_rms_mm", describe(pinhole));

  EXPECT_GT(low.count, 2000);
  EXPECT_NEAR(high.rms_total_mm / low.rms_total_mm, 3.0, 0.1);
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(high.rms_mm[axis] / low.rms_mm[axis], 3.0, 0.1) << axis;
  EXPECT_GT(low.rms_mm.z(), low.rms_mm.x());  // depth dominates
  EXPECT_GT(low.rms_mm.z(), low.rms_mm.y());
  EXPECT_LT(low.rms_total_mm, 0.3);  // the sensor's reported accuracy
  EXPECT_GT(pinhole.rms_total_mm, 1.0);
  EXPECT_GT(pinhole.rms_total_mm, 20 * high.rms_total_mm);
}

}  // namespace
}  // namespace touchcloud::optics
