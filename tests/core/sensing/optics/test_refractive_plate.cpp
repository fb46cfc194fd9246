// Plate and rig configuration: validation names the field; frames change consistently.
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "optics_fixture.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/optics/refractive_plate.hpp"
#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::optics {
namespace {

std::string validation_message(const RefractivePlate& plate) {
  try {
    plate.validate();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RefractivePlate, DefaultsAreValid) { EXPECT_NO_THROW(RefractivePlate().validate()); }

TEST(RefractivePlate, ValidationNamesTheFieldAndTheRule) {
  RefractivePlate plate;
  plate.normal = {0, 0, 0.9};
  EXPECT_NE(validation_message(plate).find("plate.normal = (0, 0, 0.9) of length 0.9: must be a unit vector"),
            std::string::npos);

  plate = {};
  plate.distance_mm = 0;
  EXPECT_NE(validation_message(plate).find("plate.distance_mm = 0: must be finite and > 0"), std::string::npos);

  plate = {};
  plate.thickness_mm = -1;
  EXPECT_NE(validation_message(plate).find("plate.thickness_mm = -1: must be finite and >= 0"), std::string::npos);

  plate = {};
  plate.thickness_mm = 0;  // collapses to one interface: allowed
  EXPECT_EQ(validation_message(plate), "");

  plate = {};
  plate.mu_silicone = 0.9;
  EXPECT_NE(validation_message(plate).find("plate.mu_silicone = 0.9: must be finite and >= 1"), std::string::npos);

  plate = {};
  plate.mu_air = std::nan("");
  plate.mu_acrylic = std::numeric_limits<double>::infinity();
  const std::string both = validation_message(plate);
  EXPECT_NE(both.find("plate.mu_air"), std::string::npos) << both;
  EXPECT_NE(both.find("plate.mu_acrylic"), std::string::npos) << both;
}

TEST(RefractivePlate, ExpressedInAnotherFrameDescribesTheSamePlanes) {
  test::RigSetup setup;
  setup.tilt_deg = 8;
  setup.azimuth_deg = 30;
  const RefractivePlate plate = test::make_plate(setup);
  const Eigen::Isometry3d other_from_this = test::right_from_left_pose();
  const RefractivePlate moved = plate.expressed_in(other_from_this);
  const Eigen::Vector3d in_plane = plate.normal.unitOrthogonal();
  for (double face : {plate.distance_mm, plate.gel_face_mm()}) {
    const Eigen::Vector3d on_face = face * plate.normal + 13.0 * in_plane;
    const Eigen::Vector3d there = other_from_this * on_face;
    EXPECT_NEAR(moved.normal.dot(there), face - plate.distance_mm + moved.distance_mm, 1e-12);
  }
  EXPECT_NEAR(moved.normal.norm(), 1.0, 1e-15);
  EXPECT_EQ(moved.thickness_mm, plate.thickness_mm);
}

TEST(StereoRig, RejectsACameraOnTheGelSideAndABadRotation) {
  test::RigSetup setup;
  const PinholeCamera camera;
  Eigen::Isometry3d far_right = test::right_from_left_pose();
  far_right.translation() = Eigen::Vector3d(-20, 0, -30);  // right centre at z = +30 mm: past the plate
  try {
    StereoRig rig(camera, camera, far_right, test::make_plate(setup));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("right camera must be on the air side"), std::string::npos) << e.what();
  }

  Eigen::Isometry3d sheared = test::right_from_left_pose();
  sheared.linear()(0, 1) += 0.01;
  try {
    StereoRig rig(camera, camera, sheared, test::make_plate(setup));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stereo_rig.right_from_left.rotation"), std::string::npos) << e.what();
  }

  setup.thickness_mm = -2;
  EXPECT_THROW(test::make_rig(setup), InputError);
}

TEST(StereoRig, CentresAndPosesAreConsistent) {
  const StereoRig rig = test::make_rig();
  EXPECT_EQ(rig.centre_mm(StereoSide::Left), Eigen::Vector3d::Zero());
  const Eigen::Vector3d right_centre = rig.centre_mm(StereoSide::Right);
  EXPECT_NEAR((right_centre - Eigen::Vector3d(test::kBaseline_mm, 0.15, -0.25)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((rig.camera_from_left(StereoSide::Right) * right_centre).norm(), 0.0, 1e-12);
  const StereoRig swapped = rig.swapped();
  EXPECT_NEAR((swapped.centre_mm(StereoSide::Right) - rig.camera_from_left(StereoSide::Right).translation()).norm(),
              0.0, 1e-12);
  EXPECT_EQ(swapped.camera(StereoSide::Left).intrinsics().fx_px, rig.camera(StereoSide::Right).intrinsics().fx_px);
}

}  // namespace
}  // namespace touchcloud::optics
