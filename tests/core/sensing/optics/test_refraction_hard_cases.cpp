// Where refraction code usually breaks (refraction.md hard cases 5-8): the
// refraction axis, points on the gel face, grazing rays, total internal reflection.
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "optics_fixture.hpp"
#include "touchcloud/optics/stereo_triangulation.hpp"

namespace touchcloud::optics {
namespace {

// Hard case 5: r = 0 has no radial direction; the output must not jump there.
TEST(RefractionHardCases, OnTheRefractionAxisOutputIsFiniteAndContinuous) {
  // Exactly on the axis (untilted plate, point straight ahead): r == 0.
  const RefractivePlate flat = test::make_plate({});
  const AirDirection on_axis = air_direction_to(flat, Eigen::Vector3d::Zero(), {0, 0, 50});
  ASSERT_EQ(on_axis.status, TraceStatus::Ok);
  EXPECT_EQ(on_axis.direction, Eigen::Vector3d::UnitZ());

  // Tilted plate, left camera: the axis is the plate normal through the centre.
  test::RigSetup setup;
  setup.tilt_deg = 9;
  setup.azimuth_deg = 100;
  const StereoRig rig = test::make_rig(setup);
  const Eigen::Vector3d n = rig.plate().normal;
  const Eigen::Vector3d e = n.unitOrthogonal();
  const Eigen::Vector3d axis_point = 55.0 * n;
  const RefractedPixel centre = project_refracted(rig, StereoSide::Left, axis_point);
  ASSERT_EQ(centre.status, TraceStatus::Ok);
  const PixelProjection straight = rig.camera(StereoSide::Left).project(n);
  EXPECT_NEAR((centre.pixel_px - straight.pixel_px).norm(), 0.0, 1e-9);

  const RefractedPixel near = project_refracted(rig, StereoSide::Left, axis_point + 1e-12 * e);
  ASSERT_EQ(near.status, TraceStatus::Ok);
  EXPECT_NEAR((near.pixel_px - centre.pixel_px).norm(), 0.0, 1e-9);
  // Away from the axis the pixel moves in proportion to r (a smooth map).
  const double per_mm_small = (project_refracted(rig, StereoSide::Left, axis_point + 1e-6 * e).pixel_px -
                               centre.pixel_px).norm() / 1e-6;
  const double per_mm_large = (project_refracted(rig, StereoSide::Left, axis_point + 1e-3 * e).pixel_px -
                               centre.pixel_px).norm() / 1e-3;
  EXPECT_GT(per_mm_small, 1.0);
  EXPECT_NEAR(per_mm_small / per_mm_large, 1.0, 1e-3);

  // And back: the pixel's ray runs along the axis through the point.
  const SiliconeRay ray = back_project_refracted(rig, StereoSide::Left, centre.pixel_px);
  ASSERT_EQ(ray.status, TraceStatus::Ok);
  EXPECT_NEAR(test::distance_to_line(axis_point, ray.origin_mm, ray.direction), 0.0, 1e-12);
}

// Hard case 6: a marker on the gel face is in the silicone; a point in the
// acrylic or in air is not.
TEST(RefractionHardCases, PointsOnTheGelFaceAreValidOthersAreNot) {
  const RefractivePlate plate = test::make_plate({});  // normal +z, gel face at z = 25
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  const double face = plate.gel_face_mm();
  const AirDirection on_face = air_direction_to(plate, centre, {6, -4, face});
  ASSERT_EQ(on_face.status, TraceStatus::Ok);
  // One ulp onto the acrylic side (h2 = -3.6e-15 mm): rounding, still on the face.
  const AirDirection rounded = air_direction_to(plate, centre, {6, -4, std::nextafter(face, 0.0)});
  ASSERT_EQ(rounded.status, TraceStatus::Ok);
  EXPECT_NEAR((rounded.direction - on_face.direction).norm(), 0.0, 1e-15);
  const AirDirection just_inside = air_direction_to(plate, centre, {6, -4, face - 1e-15});
  EXPECT_EQ(just_inside.status, TraceStatus::Ok);
  // The face point is where its own ray starts.
  const SiliconeRay ray = trace_into_silicone(plate, centre, on_face.direction);
  ASSERT_EQ(ray.status, TraceStatus::Ok);
  EXPECT_NEAR((ray.origin_mm - Eigen::Vector3d(6, -4, face)).norm(), 0.0, 1e-12);

  EXPECT_EQ(air_direction_to(plate, centre, {6, -4, face - 1e-6}).status, TraceStatus::PointNotInSilicone);
  EXPECT_EQ(air_direction_to(plate, centre, {6, -4, face - 2.5}).status, TraceStatus::PointNotInSilicone);  // acrylic
  EXPECT_EQ(air_direction_to(plate, centre, {6, -4, 10}).status, TraceStatus::PointNotInSilicone);          // air
  EXPECT_EQ(air_direction_to(plate, centre, {6, -4, -10}).status, TraceStatus::PointNotInSilicone);  // behind
  EXPECT_EQ(air_direction_to(plate, {0, 0, 30}, {6, -4, 40}).status, TraceStatus::CameraNotInAir);

  const StereoRig rig = test::make_rig();
  EXPECT_EQ(project_refracted(rig, StereoSide::Right, {6, -4, 22}).status, TraceStatus::PointNotInSilicone);

  // With no acrylic, a point on the face is reached in a straight line.
  RefractivePlate bare = plate;
  bare.thickness_mm = 0;
  const Eigen::Vector3d on_bare_face(6, -4, bare.gel_face_mm());
  const AirDirection straight = air_direction_to(bare, centre, on_bare_face);
  ASSERT_EQ(straight.status, TraceStatus::Ok);
  EXPECT_NEAR((straight.direction - on_bare_face.normalized()).norm(), 0.0, 1e-15);
  const AirDirection below = air_direction_to(bare, centre, {6, -4, bare.gel_face_mm() + 1e-9});
  ASSERT_EQ(below.status, TraceStatus::Ok);
  EXPECT_NEAR((below.direction - straight.direction).norm(), 0.0, 1e-10);
  EXPECT_LE(below.iterations, 8);
}

// Hard case 7: near-grazing paths converge; what the camera cannot see is
// "out of view", not an error.
TEST(RefractionHardCases, GrazingRaysConvergeAndFallOutOfView) {
  const StereoRig rig = test::make_rig();
  const RefractivePlate& plate = rig.plate();
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (double r : {1e2, 1e4, 1e6, 1e8}) {
    const Eigen::Vector3d point(r, 0.3 * r, plate.gel_face_mm() + 2.0);
    const AirDirection air = air_direction_to(plate, centre, point);
    ASSERT_EQ(air.status, TraceStatus::Ok) << r;
    EXPECT_TRUE(air.direction.allFinite());
    EXPECT_LE(air.iterations, 60) << r;
    // The returned path does reach the point.
    const SiliconeRay ray = trace_into_silicone(plate, centre, air.direction);
    ASSERT_EQ(ray.status, TraceStatus::Ok) << r;
    EXPECT_LE(test::distance_to_line(point, ray.origin_mm, ray.direction), 1e-12 * r) << r;
    const RefractedPixel pixel = project_refracted(rig, StereoSide::Left, point);
    EXPECT_EQ(pixel.status, TraceStatus::OutOfView) << r;
    EXPECT_TRUE(pixel.pixel_px.allFinite());
  }

  // An air ray almost along the plate enters the silicone at the critical angle.
  const Eigen::Vector3d grazing = Eigen::Vector3d(1.0, 0.0, 1e-8).normalized();
  const SiliconeRay ray = trace_into_silicone(plate, centre, grazing);
  ASSERT_EQ(ray.status, TraceStatus::Ok);
  EXPECT_TRUE(ray.origin_mm.allFinite());
  EXPECT_NEAR(std::acos(ray.direction.z()), std::asin(1.0 / 1.41), 1e-7);
  EXPECT_EQ(trace_into_silicone(plate, centre, Eigen::Vector3d::UnitX()).status, TraceStatus::MissesPlate);
  EXPECT_EQ(trace_into_silicone(plate, centre, -Eigen::Vector3d::UnitZ()).status, TraceStatus::MissesPlate);

  // Pixels off the image: a status, for rays and for triangulation.
  EXPECT_EQ(back_project_refracted(rig, StereoSide::Left, {-3, 100}).status, TraceStatus::OutOfView);
  EXPECT_EQ(back_project_refracted(rig, StereoSide::Right, {100, 720}).status, TraceStatus::OutOfView);
  const TriangulatedPoint off = triangulate_refractive(rig, {640, 360}, {1500, 360});
  EXPECT_EQ(off.status, TriangulationStatus::RightRayInvalid);
  EXPECT_EQ(off.right_ray, TraceStatus::OutOfView);
  EXPECT_TRUE(off.point_mm.allFinite());
}

// Hard case 8: indices that make total internal reflection possible.
TEST(RefractionHardCases, TotalInternalReflectionIsAnInvalidStatus) {
  test::RigSetup setup;
  setup.mu_air = 1.6;
  setup.mu_acrylic = 1.3;
  setup.mu_silicone = 1.0;
  const StereoRig rig = test::make_rig(setup);

  // The image corner is ~47 deg off axis: 1.6 sin(47) > 1.0, reflected at the gel face.
  const SiliconeRay corner = back_project_refracted(rig, StereoSide::Left, {0, 0});
  EXPECT_EQ(corner.status, TraceStatus::TotalInternalReflection);
  EXPECT_TRUE(corner.origin_mm.allFinite() && corner.direction.allFinite());
  // At 60 deg already the air/acrylic face reflects (1.6 sin 60 > 1.3).
  const Eigen::Vector3d steep(std::sin(std::numbers::pi / 3), 0, std::cos(std::numbers::pi / 3));
  EXPECT_EQ(trace_into_silicone(rig.plate(), Eigen::Vector3d::Zero(), steep).status,
            TraceStatus::TotalInternalReflection);

  const TriangulatedPoint pair = triangulate_refractive(rig, {0, 0}, {640, 360});
  EXPECT_EQ(pair.status, TriangulationStatus::LeftRayInvalid);
  EXPECT_EQ(pair.left_ray, TraceStatus::TotalInternalReflection);
  EXPECT_TRUE(pair.point_mm.allFinite());

  // Near the image centre light still gets through, and forward projection
  // (always possible in this direction of travel) agrees with it.
  const SiliconeRay centre = back_project_refracted(rig, StereoSide::Left, {598.6, 377.1});
  ASSERT_EQ(centre.status, TraceStatus::Ok);
  for (double depth : {0.0, 10.0, 40.0}) {
    const RefractedPixel back = project_refracted(rig, StereoSide::Left, centre.origin_mm + depth * centre.direction);
    ASSERT_EQ(back.status, TraceStatus::Ok);
    EXPECT_NEAR((back.pixel_px - Eigen::Vector2d(598.6, 377.1)).norm(), 0.0, 1e-9);
  }
  const Eigen::Vector3d far_off(200, 0, rig.plate().gel_face_mm() + 5);
  const AirDirection air = air_direction_to(rig.plate(), Eigen::Vector3d::Zero(), far_off);
  ASSERT_EQ(air.status, TraceStatus::Ok);
  EXPECT_LT(air.direction.z(), std::cos(std::asin(1.0 / 1.6)) + 1e-3);  // just inside the critical cone
  EXPECT_GT(air.direction.z(), std::cos(std::asin(1.0 / 1.6)));
}

}  // namespace
}  // namespace touchcloud::optics
