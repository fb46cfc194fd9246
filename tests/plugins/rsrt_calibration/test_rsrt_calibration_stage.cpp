// The calibration pipeline as a user runs it: simulated presses through the
// true sensor file, the nominal scene as the initial guess; the sensor file
// it writes describes the true plate.
#include <cmath>

#include "pipeline_fixture.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

class RsrtCalibrationStage : public touchcloud::test::PipelineFixture {
 protected:
  std::string pipeline(const std::string& press_params) {
    const auto src = test::source_dir().string();
    return "stages:\n  - id: presses\n    loop:\n      max_iterations: 40\n      until: press.last_press\n"
           "      stages:\n"
           "        - id: press\n          plugin: checkerboard_press\n"
           "          params: {sensor: " + src + "/sample_clouds/gelstereo_palm2/sensor_true.yaml, " + press_params +
           "}\n"
           "        - id: calibrate\n          plugin: rsrt_calibration\n"
           "          params: {sensor: " + src + "/sample_clouds/fox_mask/scene.yaml, output: calibrated.yaml}\n"
           "          inputs: {corners: press.corners}\n";
  }
};

TEST_F(RsrtCalibrationStage, WritesASensorFileWithTheTruePlate) {
  Pipeline p = load(pipeline("random_presses: 24"));
  RunOptions o;
  o.quiet = true;
  o.seed = 3;
  o.out_dir = dir_ / "out";
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(r.record.metrics.at("calibrate.press_corners").values.size(), 24u);
  const auto calibrated = sensor::load_gelstereo_sensor(dir_ / "out/calibrated.yaml");
  const auto truth = sensor::load_gelstereo_sensor(test::source_dir() / "sample_clouds/gelstereo_palm2/sensor_true.yaml");
  const auto plate = sensor::make_stereo_rig(calibrated, true, true).plate();
  const auto true_plate = sensor::make_stereo_rig(truth, true, true).plate();
  EXPECT_NEAR(plate.distance_mm, true_plate.distance_mm, 0.2);
  EXPECT_LT(std::acos(std::min(1.0, plate.normal.dot(true_plate.normal))) * 180 / M_PI, 0.1);
  EXPECT_NEAR(calibrated.plate.mu_silicone, 1.45, 0.005);
  EXPECT_NEAR(calibrated.plate.tilt_deg.x(), 1.5, 0.1);
  EXPECT_NEAR(calibrated.plate.tilt_deg.y(), -2.0, 0.1);
  const auto& m = r.record.metrics;
  EXPECT_LT(m.at("calibrate.mean_corner_error_after_mm").values.at(0), 0.1);
  EXPECT_GT(m.at("calibrate.mean_corner_error_before_mm").values.at(0),
            m.at("calibrate.mean_corner_error_after_mm").values.at(0));
  EXPECT_LT(m.at("calibrate.sigma_mu_silicone").values.at(0), 0.005);
  EXPECT_NEAR(m.at("calibrate.mu_silicone").values.at(0), calibrated.plate.mu_silicone, 1e-9);
}

TEST_F(RsrtCalibrationStage, FlatPressesFailTheRunAsBadInput) {
  Pipeline p = load(pipeline("presses: [0, 0, 5, 0, 0, 7, 0, 0, 9]"));
  RunOptions o;
  o.quiet = true;
  o.out_dir = dir_ / "out";
  try {
    run_pipeline(p, o);
    FAIL() << "flat presses were accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(std::string(e.what()).find("flat presses") != std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out/calibrated.yaml"));
}

TEST_F(RsrtCalibrationStage, WithoutPressesOnEitherInputTheRunIsBadInput) {
  const auto src = test::source_dir().string();
  Pipeline p = load("stages:\n  - id: calibrate\n    plugin: rsrt_calibration\n    params: {sensor: " + src +
                    "/sample_clouds/fox_mask/scene.yaml, output: calibrated.yaml}\n");
  RunOptions o;
  o.quiet = true;
  o.out_dir = dir_ / "out";
  try {
    run_pipeline(p, o);
    FAIL() << "a calibration without presses ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("connect exactly one of the inputs 'corners'"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out/calibrated.yaml"));
}
