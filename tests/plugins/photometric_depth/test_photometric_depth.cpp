// photometric_depth: the stage refuses images of another size or sensor than
// its calibration's, and a calibration file without them; the solver itself
// is tested in tests/imaging.
#include <gtest/gtest.h>

#include "stage_harness.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

std::filesystem::path write_calibration(const TempDir& dir, const std::string& sensor, int w, int h) {
  sensor::PhotometricCalibration c;
  c.sensor = sensor;
  c.width_px = w;
  c.height_px = h;
  c.mm_per_px = 0.06;
  c.gel_thickness_mm = 2.5;
  c.gx.assign(20, 0.0);
  c.gy.assign(20, 0.0);
  c.gx[1] = 1.0;
  const auto file = dir / (sensor + ".yaml");
  sensor::write_photometric_calibration(c, file);
  return file;
}

MonoColourFramePtr frame(int w, int h, const std::string& sensor) {
  auto f = std::make_shared<MonoColourFrame>();
  f->image = cv::Mat(h, w, CV_8UC3, cv::Scalar::all(120));
  f->sensor = sensor;
  return f;
}

}  // namespace

TEST(PhotometricDepth, RefusesAnImageOfAnotherSizeOrSensorThanTheCalibrations) {
  TempDir dir;
  StageHarness stage("photometric_depth", {{"calibration", write_calibration(dir, "gelsight_mini", 320, 240).string()}});
  stage.configure();
  const std::string size = input_error_of([&] {
    stage.process({{"image", frame(160, 120, "gelsight_mini")}, {"reference", frame(320, 240, "gelsight_mini")}},
                  {"height"});
  });
  EXPECT_NE(size.find("input 'image': the image is 160 x 120 px"), std::string::npos) << size;
  EXPECT_NE(size.find("is for 320 x 240 px"), std::string::npos) << size;
  const std::string sensor = input_error_of([&] {
    stage.process({{"image", frame(320, 240, "gelsight_r15")}, {"reference", frame(320, 240, "gelsight_r15")}},
                  {"height"});
  });
  EXPECT_NE(sensor.find("sensor 'gelsight_r15'"), std::string::npos) << sensor;
  EXPECT_NE(sensor.find("sensor 'gelsight_mini'"), std::string::npos) << sensor;
  // The same sensor and size: a flat height map.
  const auto map = stage.process_one<HeightMapPtr>(
      {{"image", frame(320, 240, "gelsight_mini")}, {"reference", frame(320, 240, "gelsight_mini")}}, "height");
  EXPECT_EQ(cv::countNonZero(map->height_mm), 0);
  EXPECT_EQ(map->sensor, "gelsight_mini");
}

TEST(PhotometricDepth, RefusesACalibrationFileWithoutItsSensorOrSize) {
  TempDir dir;
  write_file(dir / "bad.yaml", "photometric_calibration:\n  degree: 1\n  gx: [0, 1, 0, 0]\n  gy: [0, 0, 1, 0]\n");
  StageHarness stage("photometric_depth", {{"calibration", (dir / "bad.yaml").string()}});
  const std::string message = input_error_of([&] { stage.configure(); });
  EXPECT_NE(message.find("photometric_calibration.sensor"), std::string::npos) << message;
  EXPECT_NE(message.find("photometric_calibration.image_size_px: is missing"), std::string::npos) << message;
}

TEST(PhotometricDepth, TheCliExitsWithTwoOnACalibrationOfAnotherImageSize) {
  TempDir dir;
  const auto calibration = write_calibration(dir, "gelsight_mini", 160, 120);
  const std::string scene = (source_dir() / "sample_clouds/fox_mask/scene_gelsight.yaml").string();
  write_file(dir / "p.yaml", "pipeline: p\nstages:\n"
             "  - id: touch\n    loop:\n      max_iterations: 300\n      until: sim.touch_done\n      stages:\n"
             "        - {id: sim, plugin: gelsight_simulator, params: {scene: " + scene + ", target_xy_mm: [0, -46]},\n"
             "           inputs: {contact: contact.state@previous}}\n"
             "        - {id: contact, plugin: stable_contact, params: {threshold_mm: 0.3, frames: 3}, inputs: {tactile: sim.tactile}}\n"
             "  - {id: depth, plugin: photometric_depth, params: {calibration: " + calibration.string() + "},\n"
             "     inputs: {image: sim.image, reference: sim.image_reference}}\n"
             "  - {id: cloud, plugin: height_to_cloud, inputs: {height: depth.height}}\n"
             "  - {id: write, plugin: cloud_writer, params: {path: c.pcd}, inputs: {cloud: cloud.cloud}}\n");
  const auto result = run_cli({"run", (dir / "p.yaml").string(), "--out", (dir / "out").string()});
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find("touchcloud: error:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("the image is 320 x 240 px, but the calibration"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("is for 160 x 120 px"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "c.pcd"));
}
