// The stage as a pipeline runs it on image files: every pair found, and bad
// input (a missing image, an image without the board, a board that cannot be
// numbered) refused with the file or parameter named.
#include <gtest/gtest.h>

#include "touchcloud/simulation/board/calibration_images.hpp"
#include "calibration_image_files.hpp"
#include "pipeline_fixture.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

class BoardImageCornersStage : public test::PipelineFixture {
 protected:
  void SetUp() override {
    const auto truth =
        sensor::load_gelstereo_sensor(test::source_dir() / "sample_clouds/gelstereo_palm2/sensor_true.yaml");
    simulation::CalibrationImageOptions options;
    options.air_pairs = 2;
    options.press_pairs = 0;
    std::mt19937_64 rng(11);
    test::write_image_pairs(dir_ / "air", simulation::render_calibration_images(truth, options, rng).air);
  }
  std::string pipeline(const std::string& params = "") {
    const auto air = (dir_ / "air").string();
    return "stages:\n  - id: corners\n    plugin: board_image_corners\n    params: {left: '" + air +
           "/left_{iteration}.png', right: '" + air + "/right_{iteration}.png'" + params + "}\n";
  }
  RunResult run(const std::string& yaml) {
    Pipeline p = load(yaml);
    RunOptions o;
    o.quiet = true;
    o.out_dir = dir_ / "out";
    return run_pipeline(p, o);
  }
  std::string first_error(const std::string& yaml) {
    const auto e = errors(yaml);
    return e.empty() ? "" : e.front().message;
  }
};

TEST_F(BoardImageCornersStage, FindsEveryPair) {
  const auto r = run(pipeline());
  EXPECT_EQ(r.record.metrics.at("corners.image_pairs").values.at(0), 2.0);
}

TEST_F(BoardImageCornersStage, AMissingImageIsNamedWithItsAbsolutePath) {
  fs::remove(dir_ / "air/left_0.png");
  std::string e = first_error(pipeline());
  EXPECT_NE(e.find((dir_ / "air/left_0.png").string() + " does not exist"), std::string::npos) << e;
  fs::remove(dir_ / "air/right_1.png");
  fs::copy(dir_ / "air/left_1.png", dir_ / "air/left_0.png");
  e = first_error(pipeline());
  EXPECT_NE(e.find("has no right image (" + (dir_ / "air/right_1.png").string() + " does not exist)"),
            std::string::npos)
      << e;
}

TEST_F(BoardImageCornersStage, AnImageWithoutTheBoardIsNamed) {
  test::write_image(dir_ / "air/right_1.png", cv::Mat(720, 1280, CV_8UC1, cv::Scalar(110)));
  try {
    run(pipeline());
    FAIL() << "an image without a board was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("right_1.png: no 9 x 6 checkerboard found"), std::string::npos) << e.what();
  }
}

TEST_F(BoardImageCornersStage, TheWrongBoardSizeIsNamed) {
  try {
    run(pipeline(", board_corners: [8, 5]"));
    FAIL() << "an 8 x 5 board was found in images of a 9 x 6 one";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("left_0.png: no 8 x 5 checkerboard found"), std::string::npos) << e.what();
  }
}

TEST_F(BoardImageCornersStage, ABoardThatCannotBeNumberedIsRefusedAtCheck) {
  const std::string e = first_error(pipeline(", board_corners: [8, 6]"));
  EXPECT_NE(e.find("looks the same turned by 180 deg"), std::string::npos) << e;
}
