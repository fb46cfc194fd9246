// Scene files: defaults, and bad input that names the field at fault.
#include <gtest/gtest.h>

#include "sim_fixture.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Loads the scene and builds the simulator (where sensor and object problems surface).
void simulate(const std::filesystem::path& file) { simulation::GelStereoSimulation(simulation::load_scene(file), 1); }

}  // namespace

TEST(SceneFile, DefaultsAreThePapersSensor) {
  TempDir dir;
  const simulation::Scene s = plane_scene(dir, "[]");
  EXPECT_EQ(s.sensor.gel.diameter_mm, 65.0);
  EXPECT_EQ(s.sensor.markers.min_spacing_mm, 1.5);
  EXPECT_EQ(s.sensor.markers.mean_spacing_mm, 1.8);
  EXPECT_EQ(s.sensor.plate.mu_air, 1.0);
  EXPECT_EQ(s.sensor.plate.mu_acrylic, 1.49);
  EXPECT_EQ(s.sensor.plate.mu_silicone, 1.41);
  EXPECT_EQ(s.sensor.cameras.left.width_px, 1280);
  EXPECT_EQ(s.sensor.cameras.left.height_px, 720);
  EXPECT_EQ(s.sensor.cameras.left.fx_px, 651.5);
  EXPECT_EQ(s.sensor.cameras.right.fx_px, 651.5);
  EXPECT_EQ(s.sensor.fps, 30.0);
  EXPECT_EQ(s.robot.press_depth_mm, 1.5);
  EXPECT_TRUE(s.effects.empty());
  // Both cameras below the plate, the right one a baseline along +x of the left.
  const Eigen::Vector3d left = s.sensor.sensor_from_left_camera().translation();
  const Eigen::Vector3d right = (s.sensor.sensor_from_left_camera() * s.sensor.cameras.right_from_left.inverse()).translation();
  EXPECT_NEAR(left.z(), -(s.sensor.plate.thickness_mm + sensor::kDefaultPlateGapMm), 1e-12);
  EXPECT_NEAR((right - left).x(), sensor::kDefaultBaselineMm, 1e-12);
  EXPECT_NEAR(left.x() + right.x(), 0.0, 1e-12);
}

TEST(SceneFile, EffectsComeAsNamesOrWithFields) {
  TempDir dir;
  const simulation::Scene s = plane_scene(dir, "[contact, {elastic_spread: {sigma_mm: 2.5}}, {marker_dropout: {probability: 0.2}}]");
  EXPECT_TRUE(s.effects.has(simulation::Effect::Contact));
  EXPECT_TRUE(s.effects.has(simulation::Effect::ElasticSpread));
  EXPECT_TRUE(s.effects.has(simulation::Effect::MarkerDropout));
  EXPECT_FALSE(s.effects.has(simulation::Effect::Render));
  EXPECT_EQ(s.effect_parameters.spread_sigma_mm, 2.5);
  EXPECT_EQ(s.effect_parameters.dropout_probability, 0.2);
}

TEST(SceneFile, UnknownEffectIsNamedWithItsPlace) {
  TempDir dir;
  const auto file = write_plane_scene(dir, "[contact, blurr]");
  try {
    simulation::load_scene(file);
    FAIL() << "an unknown effect was accepted";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
    const auto& d = e.diagnostics()[0];
    EXPECT_TRUE(has(d.message, "effects[1]: unknown effect 'blurr'")) << d.message;
    EXPECT_TRUE(has(d.message, "known: contact, elastic_spread")) << d.message;
    EXPECT_EQ(d.where.file, file.string());
    EXPECT_EQ(d.where.line, 3);  // "effects:" follows the object and an empty line
  }
}

TEST(SceneFile, UnknownFieldsAndEffectFieldsAreErrors) {
  TempDir dir;
  const std::string m1 = input_error([&] { plane_scene(dir, "[]", "sensor: {plate: {thicknes_mm: 3}}"); });
  EXPECT_TRUE(has(m1, "sensor.plate.thicknes_mm: unknown field")) << m1;
  EXPECT_TRUE(has(m1, "thickness_mm")) << m1;  // the known fields are listed
  const std::string m2 = input_error([&] { plane_scene(dir, "[{blur: {sigma: 2}}]"); });
  EXPECT_TRUE(has(m2, "effects.blur.sigma: unknown field")) << m2;
}

TEST(SceneFile, NonPositiveSizesAreNamed) {
  TempDir dir;
  for (const auto& [extra, field] : std::vector<std::pair<std::string, std::string>>{
           {"sensor: {gel: {diameter_mm: 0}}", "sensor.gel.diameter_mm: 0 must be > 0"},
           {"sensor: {plate: {thickness_mm: -2}}", "sensor.plate.thickness_mm: -2 must be > 0"},
           {"sensor: {markers: {min_spacing_mm: 0}}", "sensor.markers.min_spacing_mm: 0 must be > 0"},
           {"sensor: {cameras: {baseline_mm: -30}}", "sensor.cameras.baseline_mm: -30 must be > 0"},
           {"sensor: {cameras: {left: {fx_px: 0}}}", "sensor.cameras.left.fx_px: 0 must be > 0"},
           {"robot: {speed_mm_s: 0}", "robot.speed_mm_s: 0 must be > 0"},
           {"robot: {approach_speed_mm_s: -1}", "robot.approach_speed_mm_s: -1 must be >= 0"},
       }) {
    const std::string m = input_error([&] { plane_scene(dir, "[]", extra); });
    EXPECT_TRUE(has(m, field)) << extra << " -> " << m;
  }
  // The object's scale sits beside its kind.
  write_file(dir / "scaled.yaml", "object: {analytic: fox_mask, scale: -1}\n");
  const std::string m = input_error([&] { simulation::load_scene(dir / "scaled.yaml"); });
  EXPECT_TRUE(has(m, "object.scale: -1 must be > 0")) << m;
}

TEST(SceneFile, UnreadableOrEmptyMeshIsNamed) {
  TempDir dir;
  write_file(dir / "missing.yaml", "object: {mesh: nowhere.stl}\n");
  std::string m = input_error([&] { simulate(dir / "missing.yaml"); });
  EXPECT_TRUE(has(m, "object.mesh")) << m;
  EXPECT_TRUE(has(m, "nowhere.stl does not exist")) << m;

  write_file(dir / "empty.stl", "");
  write_file(dir / "empty.yaml", "object: {mesh: empty.stl}\n");
  m = input_error([&] { simulate(dir / "empty.yaml"); });
  EXPECT_TRUE(has(m, "object.mesh")) << m;
  EXPECT_TRUE(has(m, "empty")) << m;

  // A PLY file with points and no faces holds no surface.
  write_file(dir / "points.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "end_header\n0 0 0\n1 0 0\n0 1 0\n");
  write_file(dir / "points.yaml", "object: {mesh: points.ply}\n");
  m = input_error([&] { simulate(dir / "points.yaml"); });
  EXPECT_TRUE(has(m, "object.mesh")) << m;
}

TEST(SceneFile, IndicesThatReflectEveryRayAreNamed) {
  // Test-only indices (air 1.6 > acrylic 1.3 > silicone 1.0) with the plate
  // turned 75 deg: every camera ray meets it at more than the 38.7 deg critical
  // angle in air, or misses it.
  TempDir dir;
  const auto file = write_plane_scene(
      dir, "[refraction]", "sensor: {plate: {mu_air: 1.6, mu_acrylic: 1.3, mu_silicone: 1.0, tilt_deg: [75, 0]}}");
  const std::string m = input_error([&] { simulate(file); });
  EXPECT_TRUE(has(m, "sensor.plate")) << m;
  EXPECT_TRUE(has(m, "totally reflected")) << m;
  // The same plate with ordinary indices lets light through (the cameras then
  // see no marker, a different error).
  const auto ordinary = write_plane_scene(dir, "[refraction]", "sensor: {plate: {tilt_deg: [75, 0]}}", "ordinary.yaml");
  try {
    simulate(ordinary);
  } catch (const InputError& e) {
    EXPECT_FALSE(has(e.what(), "totally reflected")) << e.what();
  }
}

TEST(SceneFile, CameraThatSeesNoMarkerIsNamed) {
  TempDir dir;
  const auto file =
      write_plane_scene(dir, "[]", "sensor: {cameras: {sensor_from_left_camera: {xyz_mm: [300, 0, -50]}}}");
  const std::string m = input_error([&] { simulate(file); });
  EXPECT_TRUE(has(m, "sensor.cameras")) << m;
  EXPECT_TRUE(has(m, "left camera sees none of the")) << m;
}

TEST(SceneFile, ConflictingRigFieldsAreRefused) {
  TempDir dir;
  const std::string m = input_error(
      [&] { plane_scene(dir, "[]", "sensor: {cameras: {plate_gap_mm: 30, sensor_from_left_camera: {xyz_mm: [0, 0, -40]}}}"); });
  EXPECT_TRUE(has(m, "give either plate_gap_mm or sensor_from_left_camera")) << m;
}
