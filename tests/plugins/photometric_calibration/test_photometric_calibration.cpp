// photometric_calibration on simulated presses of the shipped ball: the fitted
// polynomial gives the ball's gradients back, the file names its sensor and
// image size, and the stage refuses what it cannot use.
#include <gtest/gtest.h>

#include "ball_calibration.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

TEST(PhotometricCalibration, BallPressesGiveTheBallsGradientsBack) {
  TempDir dir;
  const auto file = calibrate_on_ball(dir, {{-1.5, -1.0}, {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}});
  const auto c = sensor::load_photometric_calibration(file);
  EXPECT_EQ(c.sensor, "gelsight_mini");
  EXPECT_EQ(c.width_px, 320);
  EXPECT_EQ(c.height_px, 240);
  EXPECT_DOUBLE_EQ(c.mm_per_px, 0.06);
  EXPECT_DOUBLE_EQ(c.gel_thickness_mm, 2.5);
  EXPECT_EQ(c.gx.size(), 20u);
  EXPECT_GT(c.samples, 4 * 5000);
  EXPECT_GT(c.max_slope, 0.5);
  std::cout << "calibration: " << c.samples << " samples, residual rms " << c.rms_gradient << ", steepest "
            << c.max_slope << "\n";
  // Residual: 8-bit colours and the ball mesh's 0.05 mm facets.
  EXPECT_LT(c.rms_gradient, 0.02);
  // The flat gel's colour gives no slope.
  EXPECT_LT(c.gradient(Eigen::Vector3d::Zero()).norm(), 0.01);
}

TEST(PhotometricCalibration, RefusesImagesOfAnotherSensorAndRunsWithoutPresses) {
  TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  StageHarness stage("photometric_calibration",
                     {{"sensor", (source_dir() / "sample_clouds/gelsight_ball/scene.yaml").string()}}, "calibrate",
                     settings);
  stage.configure();
  auto frame = [](int width, const std::string& sensor) {
    auto f = std::make_shared<MonoColourFrame>();
    f->image = cv::Mat(240, width, CV_8UC3, cv::Scalar::all(100));
    f->sensor = sensor;
    return MonoColourFramePtr(f);
  };
  const std::string other = input_error_of([&] {
    stage.process({{"image", frame(320, "gelsight_r15")}, {"reference", frame(320, "gelsight_mini")}}, {});
  });
  EXPECT_NE(other.find("'gelsight_r15'"), std::string::npos) << other;
  EXPECT_NE(other.find("'gelsight_mini'"), std::string::npos) << other;
  const std::string size = input_error_of([&] {
    stage.process({{"image", frame(160, "gelsight_mini")}, {"reference", frame(320, "gelsight_mini")}}, {});
  });
  EXPECT_NE(size.find("160 x 240 px"), std::string::npos) << size;
  EXPECT_NE(size.find("320 x 240"), std::string::npos) << size;
  // A frame without a press is skipped; a run with none fails at the end.
  stage.process({{"image", frame(320, "gelsight_mini")}, {"reference", frame(320, "gelsight_mini")}}, {});
  const std::string none = input_error_of([&] { stage.finish(); });
  EXPECT_NE(none.find("none of the 1 frames shows a ball press"), std::string::npos) << none;
  EXPECT_FALSE(std::filesystem::exists(dir / "photometric_calibration.yaml"));
}

TEST(PhotometricCalibration, TheSensorMustBeOfFamilyGelSight) {
  StageHarness stage("photometric_calibration",
                     {{"sensor", (source_dir() / "sample_clouds/fox_mask/scene.yaml").string()}});
  std::string message;
  try {
    stage.configure();
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("family: gelsight"), std::string::npos) << message;
}
