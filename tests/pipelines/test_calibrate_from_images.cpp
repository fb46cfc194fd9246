// pipelines/calibrate_from_images.yaml on a rendered calibration set with
// known truth (sample_clouds/gelstereo_palm2/sensor_true.yaml): the sensor
// file it writes has the true cameras (intrinsics within 0.5 %) and the true
// plate (as close as the simulated-press calibration gets); summary.json has
// a residual for every image pair; bad images leave no sensor file behind.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "calibration_image_files.hpp"
#include "test_support.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

const fs::path kTruthFile = "sample_clouds/gelstereo_palm2/sensor_true.yaml";

class CalibrateFromImages : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    images_ = new test::TempDir;
    const auto truth = sensor::load_gelstereo_sensor(test::source_dir() / kTruthFile);
    simulation::CalibrationImageOptions options;  // 12 pairs in air, 1 grey level of noise
    options.press_pairs = 24;
    options.air_pairs = 20;
    std::mt19937_64 rng(2026);
    const auto set = simulation::render_calibration_images(truth, options, rng);
    test::write_image_pairs(*images_ / "air", set.air);
    test::write_image_pairs(*images_ / "press", set.press);
  }
  static void TearDownTestSuite() { delete images_; }

  RunResult run(const fs::path& images, const fs::path& out) {
    std::vector<Override> set;
    for (const char* folder : {"air", "press"})
      for (const char* side : {"left", "right"})
        set.push_back({std::string(folder) + "_corners." + side,
                       (images / folder / (std::string(side) + "_{iteration}.png")).string()});
    PluginRegistry registry;
    Pipeline p = Pipeline::load(test::source_dir() / "pipelines/calibrate_from_images.yaml", set, registry);
    RunOptions o;
    o.quiet = true;
    o.out_dir = out;
    return run_pipeline(p, o);
  }
  static test::TempDir* images_;
  test::TempDir dir_;
};
test::TempDir* CalibrateFromImages::images_ = nullptr;

double percent(double estimate, double truth) { return 100 * std::abs(estimate - truth) / std::abs(truth); }

}  // namespace

TEST_F(CalibrateFromImages, WritesTheTrueCamerasAndPlate) {
  const RunResult r = run(images_->path(), dir_ / "out");
  const auto truth = sensor::load_gelstereo_sensor(test::source_dir() / kTruthFile);
  const auto calibrated = sensor::load_gelstereo_sensor(dir_ / "out/calibrated_sensor.yaml");

  for (const auto& [e, t, side] : {std::tuple{&calibrated.cameras.left, &truth.cameras.left, "left"},
                                   std::tuple{&calibrated.cameras.right, &truth.cameras.right, "right"}}) {
    std::cout << side << ": fx " << percent(e->fx_px, t->fx_px) << " %, fy " << percent(e->fy_px, t->fy_px)
              << " %, cx " << percent(e->cx_px, t->cx_px) << " %, cy " << percent(e->cy_px, t->cy_px) << " % off\n";
    EXPECT_LT(percent(e->fx_px, t->fx_px), 0.5) << side;
    EXPECT_LT(percent(e->fy_px, t->fy_px), 0.5) << side;
    EXPECT_LT(percent(e->cx_px, t->cx_px), 0.5) << side;
    EXPECT_LT(percent(e->cy_px, t->cy_px), 0.5) << side;
  }
  const Eigen::Isometry3d& rl = calibrated.cameras.right_from_left;
  const double translation_mm = (rl.translation() - truth.cameras.right_from_left.translation()).norm();
  const double rotation_deg =
      Eigen::AngleAxisd(rl.linear() * truth.cameras.right_from_left.linear().transpose()).angle() * 180 / M_PI;
  EXPECT_LT(translation_mm, 0.2);
  EXPECT_LT(rotation_deg, 0.05);

  // The plate in the left camera frame, to the simulated calibration's
  // tolerances (tests/plugins/rsrt_calibration: 0.2 mm, 0.1 deg, 0.005).
  const auto plate = sensor::make_stereo_rig(calibrated, true, true).plate();
  const auto true_plate = sensor::make_stereo_rig(truth, true, true).plate();
  const double normal_deg = std::acos(std::min(1.0, plate.normal.dot(true_plate.normal))) * 180 / M_PI;
  std::cout << "right_from_left " << translation_mm << " mm, " << rotation_deg << " deg off; plate d_xy "
            << plate.distance_mm - true_plate.distance_mm << " mm, normal " << normal_deg << " deg, mu_silicone "
            << plate.mu_silicone - true_plate.mu_silicone << " off\n";
  EXPECT_NEAR(plate.distance_mm, true_plate.distance_mm, 0.2);
  EXPECT_LT(normal_deg, 0.1);
  EXPECT_NEAR(calibrated.plate.mu_silicone, truth.plate.mu_silicone, 0.005);
  EXPECT_NEAR(calibrated.plate.tilt_deg.x(), truth.plate.tilt_deg.x(), 0.1);
  EXPECT_NEAR(calibrated.plate.tilt_deg.y(), truth.plate.tilt_deg.y(), 0.1);

  // A residual for every image pair, and small.
  const auto& m = r.record.metrics;
  for (const char* key : {"cameras.image_rms_left_px", "cameras.image_rms_right_px"}) {
    const auto& values = m.at(key).values;
    ASSERT_EQ(values.size(), 20u) << key;
    for (double v : values) EXPECT_LT(v, 0.15) << key;
  }
  const auto& press = m.at("calibrate.press_corner_error_mm").values;
  ASSERT_EQ(press.size(), 24u);
  for (double v : press) EXPECT_LT(v, 0.02);
  EXPECT_NE(r.record.notes.at("cameras.image_residuals").find("left_11.png"), std::string::npos);
  EXPECT_NE(r.record.notes.at("calibrate.press_residuals").find("left_23.png"), std::string::npos);
}

TEST_F(CalibrateFromImages, APressImageWithoutTheBoardLeavesNoSensorFile) {
  test::TempDir bad;
  fs::copy(images_->path(), bad.path(), fs::copy_options::recursive);
  test::write_image(bad / "press/left_7.png", cv::Mat(720, 1280, CV_8UC1, cv::Scalar(110)));
  try {
    run(bad.path(), dir_ / "out");
    FAIL() << "a press image without a board was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find((bad / "press/left_7.png").string() + ": no 6 x 5 checkerboard found"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "out/calibrated_sensor.yaml"));
  EXPECT_FALSE(fs::exists(dir_ / "out/summary.json"));
}
