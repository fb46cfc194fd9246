// Forward projection (point -> pixel) and back-projection (pixel -> silicone
// ray) through the plate: limits that reduce to known models, and round trips
// over the dome (refraction.md hard cases 1-4).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "optics_fixture.hpp"
#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::optics {
namespace {

constexpr StereoSide kSides[] = {StereoSide::Left, StereoSide::Right};

// Hard case 1: with all indices equal the plate is invisible.
TEST(ForwardProjection, EqualIndicesGiveThePinholeProjection) {
  for (double mu : {1.0, 1.49}) {
    test::RigSetup setup;
    setup.tilt_deg = 7;
    setup.azimuth_deg = 40;
    setup.mu_air = setup.mu_acrylic = setup.mu_silicone = mu;
    const StereoRig rig = test::make_rig(setup);
    int compared = 0;
    for (const Eigen::Vector3d& point : test::dome_points(rig, 2000, 3)) {
      for (StereoSide side : kSides) {
        const RefractedPixel refracted = project_refracted(rig, side, point);
        const PixelProjection pinhole = rig.camera(side).project(rig.camera_from_left(side) * point);
        ASSERT_EQ(refracted.status, pinhole.status);
        if (pinhole.status != TraceStatus::Ok) continue;
        EXPECT_NEAR((refracted.pixel_px - pinhole.pixel_px).norm(), 0.0, 1e-9);
        // And the silicone ray is the camera ray.
        const SiliconeRay ray = back_project_refracted(rig, side, refracted.pixel_px);
        ASSERT_EQ(ray.status, TraceStatus::Ok);
        const Eigen::Vector3d camera_ray =
            rig.camera_from_left(side).linear().transpose() * rig.camera(side).back_project(pinhole.pixel_px).direction;
        EXPECT_NEAR((ray.direction - camera_ray).norm(), 0.0, 1e-12);
        EXPECT_NEAR(test::distance_to_line(ray.origin_mm, rig.centre_mm(side), camera_ray), 0.0, 1e-12);
        ++compared;
      }
    }
    EXPECT_GT(compared, 2000);
  }
}

// Hard case 2: only index ratios matter.
TEST(ForwardProjection, ScalingAllIndicesChangesNothing) {
  test::RigSetup setup;
  setup.tilt_deg = 10;
  setup.azimuth_deg = 200;
  const StereoRig rig = test::make_rig(setup);
  for (double k : {1.7, 2.9}) {
    test::RigSetup scaled_setup = setup;
    scaled_setup.mu_air *= k;
    scaled_setup.mu_acrylic *= k;
    scaled_setup.mu_silicone *= k;
    const StereoRig scaled = test::make_rig(scaled_setup);
    double worst_px = 0, worst_direction = 0, worst_origin_mm = 0;
    for (const Eigen::Vector3d& point : test::dome_points(rig, 1000, 5)) {
      for (StereoSide side : kSides) {
        const RefractedPixel a = project_refracted(rig, side, point);
        const RefractedPixel b = project_refracted(scaled, side, point);
        ASSERT_EQ(a.status, b.status);
        if (a.status != TraceStatus::Ok) continue;
        worst_px = std::max(worst_px, (a.pixel_px - b.pixel_px).norm());
        const SiliconeRay ray_a = back_project_refracted(rig, side, a.pixel_px);
        const SiliconeRay ray_b = back_project_refracted(scaled, side, a.pixel_px);
        ASSERT_EQ(ray_a.status, TraceStatus::Ok);
        ASSERT_EQ(ray_b.status, TraceStatus::Ok);
        worst_direction = std::max(worst_direction, (ray_a.direction - ray_b.direction).norm());
        worst_origin_mm = std::max(worst_origin_mm, (ray_a.origin_mm - ray_b.origin_mm).norm());
      }
    }
    EXPECT_LE(worst_px, 1e-12) << "k = " << k;
    EXPECT_LE(worst_direction, 1e-12) << "k = " << k;
    EXPECT_LE(worst_origin_mm, 1e-12) << "k = " << k;
  }
}

// An independent model of one air/silicone interface n . X = face_mm, in
// scalar Snell's law: the air angle by bisection, the rays by angles.
struct SingleInterface {
  Eigen::Vector3d n;
  double face_mm, mu_air, mu_gel;

  Eigen::Vector3d air_direction_to(const Eigen::Vector3d& centre, const Eigen::Vector3d& point) const {
    const double h_air = face_mm - n.dot(centre), h_gel = n.dot(point) - face_mm;
    const Eigen::Vector3d w = (point - centre) - (point - centre).dot(n) * n;
    const double r = w.norm();
    double lo = 0, hi = std::numbers::pi / 2;
    for (int i = 0; i < 200; ++i) {
      const double air = 0.5 * (lo + hi);
      const double gel = std::asin(mu_air * std::sin(air) / mu_gel);
      (h_air * std::tan(air) + h_gel * std::tan(gel) < r ? lo : hi) = air;
    }
    const double air = 0.5 * (lo + hi);
    return std::cos(air) * n + std::sin(air) * w / r;
  }
  // The silicone ray as (a point on it, direction).
  std::pair<Eigen::Vector3d, Eigen::Vector3d> silicone_ray(const Eigen::Vector3d& centre,
                                                           const Eigen::Vector3d& air_direction) const {
    const double cos_air = air_direction.dot(n);
    const Eigen::Vector3d e = (air_direction - cos_air * n).normalized();
    const double gel = std::asin(mu_air * std::sin(std::acos(cos_air)) / mu_gel);
    return {centre + (face_mm - n.dot(centre)) / cos_air * air_direction, std::cos(gel) * n + std::sin(gel) * e};
  }
};

// Hard case 3: a layer that does not refract, or has no thickness, vanishes.
TEST(ForwardProjection, CollapsedLayersEqualOneInterface) {
  struct Case {
    const char* name;
    test::RigSetup setup;
    double face_mm;
  };
  test::RigSetup base;
  base.tilt_deg = 6;
  base.azimuth_deg = 75;
  Case acrylic_as_air{"mu_acrylic = mu_air", base, base.distance_mm + base.thickness_mm};
  acrylic_as_air.setup.mu_acrylic = base.mu_air;
  Case acrylic_as_silicone{"mu_acrylic = mu_silicone", base, base.distance_mm};
  acrylic_as_silicone.setup.mu_acrylic = base.mu_silicone;
  Case no_acrylic{"thickness 0", base, base.distance_mm};
  no_acrylic.setup.thickness_mm = 0;

  for (const Case& c : {acrylic_as_air, acrylic_as_silicone, no_acrylic}) {
    const StereoRig rig = test::make_rig(c.setup);
    const SingleInterface single{rig.plate().normal, c.face_mm, c.setup.mu_air, c.setup.mu_silicone};
    double worst_px = 0, worst_line_mm = 0;
    int compared = 0;
    for (const Eigen::Vector3d& point : test::dome_points(rig, 1000, 9)) {
      for (StereoSide side : kSides) {
        const RefractedPixel got = project_refracted(rig, side, point);
        const Eigen::Vector3d air = single.air_direction_to(rig.centre_mm(side), point);
        const PixelProjection expected = rig.camera(side).project(rig.camera_from_left(side).linear() * air);
        ASSERT_EQ(got.status, expected.status) << c.name;
        if (got.status != TraceStatus::Ok) continue;
        worst_px = std::max(worst_px, (got.pixel_px - expected.pixel_px).norm());

        const SiliconeRay ray = back_project_refracted(rig, side, got.pixel_px);
        ASSERT_EQ(ray.status, TraceStatus::Ok);
        const Eigen::Vector3d pixel_air =
            rig.camera_from_left(side).linear().transpose() * rig.camera(side).back_project(got.pixel_px).direction;
        const auto [on_line, direction] = single.silicone_ray(rig.centre_mm(side), pixel_air);
        worst_line_mm = std::max({worst_line_mm, (ray.direction - direction).norm(),
                                  test::distance_to_line(ray.origin_mm, on_line, direction)});
        ++compared;
      }
    }
    EXPECT_GT(compared, 1000) << c.name;
    EXPECT_LE(worst_px, 1e-9) << c.name;
    EXPECT_LE(worst_line_mm, 1e-9) << c.name;
  }
}

// Hard case 4: round trips over 10^4 dome points, both cameras, plate tilted up to 10 deg.
TEST(ForwardProjection, DomeRoundTrips) {
  constexpr int kPoints = 10000;
  struct Tilt {
    double tilt_deg, azimuth_deg;
  };
  double worst_point_to_ray_mm = 0, worst_pixel_px = 0;
  int max_iterations = 0;
  for (const Tilt tilt : {Tilt{0, 0}, Tilt{4, 30}, Tilt{7, 135}, Tilt{10, 250}}) {
    test::RigSetup setup;
    setup.tilt_deg = tilt.tilt_deg;
    setup.azimuth_deg = tilt.azimuth_deg;
    const StereoRig rig = test::make_rig(setup);
    const std::vector<Eigen::Vector3d> points = test::dome_points(rig, kPoints, 17);
    for (StereoSide side : kSides) {
      // point -> pixel -> ray: the ray passes through the point.
      int seen = 0;
      for (const Eigen::Vector3d& point : points) {
        const RefractedPixel pixel = project_refracted(rig, side, point);
        if (pixel.status == TraceStatus::OutOfView) {
          EXPECT_FALSE(rig.camera(side).in_view(pixel.pixel_px));
          continue;
        }
        ASSERT_EQ(pixel.status, TraceStatus::Ok);
        ++seen;
        max_iterations = std::max(max_iterations, air_direction_to(rig.plate(), rig.centre_mm(side), point).iterations);
        const SiliconeRay ray = back_project_refracted(rig, side, pixel.pixel_px);
        ASSERT_EQ(ray.status, TraceStatus::Ok);
        EXPECT_GE((point - ray.origin_mm).dot(ray.direction), 0.0);
        worst_point_to_ray_mm = std::max(worst_point_to_ray_mm, test::distance_to_line(point, ray.origin_mm, ray.direction));
      }
      EXPECT_GT(seen, kPoints * 7 / 10) << "tilt " << tilt.tilt_deg << " " << to_string(side);

      // pixel -> ray -> point -> pixel: the pixel comes back.
      std::mt19937 rng(23);
      const CameraIntrinsics& k = rig.camera(side).intrinsics();
      std::uniform_real_distribution<double> u(0.0, k.width_px - 1.0), v(0.0, k.height_px - 1.0), depth(0.0, 70.0);
      for (int i = 0; i < kPoints; ++i) {
        const Eigen::Vector2d pixel(u(rng), v(rng));
        const SiliconeRay ray = back_project_refracted(rig, side, pixel);
        ASSERT_EQ(ray.status, TraceStatus::Ok);
        const RefractedPixel back = project_refracted(rig, side, ray.origin_mm + depth(rng) * ray.direction);
        ASSERT_EQ(back.status, TraceStatus::Ok) << to_string(back.status);
        worst_pixel_px = std::max(worst_pixel_px, (back.pixel_px - pixel).norm());
      }
    }
  }
  std::cout << "[ dome round trips ] point->pixel->ray max distance " << worst_point_to_ray_mm
            << " mm; pixel->ray->point->pixel max error " << worst_pixel_px << " px; max solver iterations "
            << max_iterations << "\n";
  ::testing::Test::RecordProperty("point_to_ray_max_mm", std::to_string(worst_point_to_ray_mm));
  ::testing::Test::RecordProperty("pixel_round_trip_max_px", std::to_string(worst_pixel_px));
  EXPECT_LE(worst_point_to_ray_mm, 1e-9);
  EXPECT_LE(worst_pixel_px, 1e-6);
  EXPECT_LE(max_iterations, 8);
}

}  // namespace
}  // namespace touchcloud::optics
