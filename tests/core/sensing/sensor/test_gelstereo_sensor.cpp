// The sensor description shared by the simulator, the sensing stages and
// calibration: read from a scene file, written and read back, and moved to
// a plate that calibration estimated.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"

using namespace touchcloud;
using touchcloud::test::TempDir;

namespace {

const std::filesystem::path kFoxScene = test::source_dir() / "sample_clouds/fox_mask/scene.yaml";

void expect_same_rig(const optics::StereoRig& a, const optics::StereoRig& b, double tol) {
  EXPECT_LT((a.plate().normal - b.plate().normal).norm(), tol);
  EXPECT_NEAR(a.plate().distance_mm, b.plate().distance_mm, tol);
  EXPECT_NEAR(a.plate().thickness_mm, b.plate().thickness_mm, tol);
  EXPECT_NEAR(a.plate().mu_silicone / a.plate().mu_air, b.plate().mu_silicone / b.plate().mu_air, tol);
  EXPECT_NEAR(a.plate().mu_acrylic / a.plate().mu_air, b.plate().mu_acrylic / b.plate().mu_air, tol);
  EXPECT_LT((a.right_from_left().matrix() - b.right_from_left().matrix()).norm(), tol);
  for (auto side : {optics::StereoSide::Left, optics::StereoSide::Right}) {
    const auto& ia = a.camera(side).intrinsics();
    const auto& ib = b.camera(side).intrinsics();
    EXPECT_EQ(ia.width_px, ib.width_px);
    EXPECT_NEAR(ia.fx_px, ib.fx_px, tol);
    EXPECT_NEAR(ia.cy_px, ib.cy_px, tol);
  }
}

}  // namespace

TEST(GelStereoSensor, ReadsTheSensorSectionOfASceneFile) {
  const auto s = sensor::load_gelstereo_sensor(kFoxScene);
  EXPECT_EQ(s.gel.diameter_mm, 65.0);
  EXPECT_EQ(s.cameras.left.fx_px, 651.5);
  EXPECT_EQ(s.cameras.right.fy_px, 652.0);  // the right camera defaults to the left one
  const auto rig = sensor::make_stereo_rig(s, true, false);
  // Untilted plate, cameras plate_gap_mm = 45 below its camera-side face.
  EXPECT_LT((rig.plate().normal - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(rig.plate().distance_mm, 45.0, 1e-12);
  EXPECT_NEAR(rig.centre_mm(optics::StereoSide::Right).x(), 30.0, 1e-12);
  // Without refraction every index is equal: straight rays.
  const auto pinhole = sensor::make_stereo_rig(s, false, false);
  EXPECT_EQ(pinhole.plate().mu_silicone, pinhole.plate().mu_air);
}

TEST(GelStereoSensor, WrittenFileReadsBackToTheSameRig) {
  TempDir dir;
  auto s = sensor::load_gelstereo_sensor(kFoxScene);
  s.plate.tilt_deg = {2.5, -1.25};
  s.plate.mu_silicone = 1.43;
  s.cameras.right.cx_px = 610.25;
  sensor::write_gelstereo_sensor(s, dir / "sensor.yaml", "test sensor\nsecond line");
  const auto back = sensor::load_gelstereo_sensor(dir / "sensor.yaml");
  expect_same_rig(sensor::make_stereo_rig(s, true, true), sensor::make_stereo_rig(back, true, true), 1e-9);
  EXPECT_EQ(back.markers.seed, s.markers.seed);
  EXPECT_FALSE(std::filesystem::exists(dir / "sensor.yaml.partial"));
}

TEST(GelStereoSensor, PlateFromCalibrationMovesTiltIndexAndDistance) {
  const auto nominal = sensor::load_gelstereo_sensor(kFoxScene);
  // A plate as calibration would report it in the left camera frame.
  optics::RefractivePlate wanted = sensor::make_stereo_rig(nominal, true, false).plate();
  wanted.normal = Eigen::Vector3d(0.05, -0.03, 1.0).normalized();
  wanted.distance_mm = 43.7;
  wanted.mu_silicone = 1.452;
  auto s = nominal;
  sensor::set_plate_from_left_frame(s, wanted);
  const auto got = sensor::make_stereo_rig(s, true, false).plate();
  EXPECT_LT((got.normal - wanted.normal).norm(), 1e-12);
  EXPECT_NEAR(got.distance_mm, 43.7, 1e-12);
  EXPECT_NEAR(got.mu_silicone, 1.452, 1e-15);
  EXPECT_NEAR(got.thickness_mm, nominal.plate.thickness_mm, 1e-15);
  // The baseline stays what it was.
  EXPECT_LT((s.cameras.right_from_left.matrix() - nominal.cameras.right_from_left.matrix()).norm(), 1e-15);
}

TEST(GelStereoSensor, BadFilesAreNamed) {
  TempDir dir;
  test::write_file(dir / "none.yaml", "name: x\n");
  try {
    sensor::load_gelstereo_sensor(dir / "none.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no 'sensor:' section"), std::string::npos) << e.what();
  }
  test::write_file(dir / "bad.yaml", "sensor:\n  plate: {thickness_mm: -2, colour: red}\n");
  try {
    sensor::load_gelstereo_sensor(dir / "bad.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("sensor.plate.thickness_mm"), std::string::npos) << m;
    EXPECT_NE(m.find("sensor.plate.colour: unknown field"), std::string::npos) << m;
    EXPECT_NE(m.find(":2:"), std::string::npos) << m;  // the line
  }
  EXPECT_THROW(sensor::load_gelstereo_sensor(dir / "missing.yaml"), InputError);
}

TEST(GelStereoSensor, AGelSightSectionIsRefusedByItsFamily) {
  TempDir dir;
  touchcloud::test::write_file(dir / "gelsight.yaml", "sensor: {family: gelsight, mm_per_px: 0.06}\n");
  const std::string message = touchcloud::test::input_error_of([&] { sensor::load_gelstereo_sensor(dir / "gelsight.yaml"); });
  EXPECT_NE(message.find("sensor.family: is gelsight"), std::string::npos) << message;
  EXPECT_EQ(message.find("mm_per_px"), std::string::npos) << message;
  // Naming the GelStereo's family reads as before.
  touchcloud::test::write_file(dir / "gelstereo.yaml", "sensor: {family: gelstereo, gel: {diameter_mm: 60}}\n");
  EXPECT_DOUBLE_EQ(sensor::load_gelstereo_sensor(dir / "gelstereo.yaml").gel.diameter_mm, 60.0);
}
