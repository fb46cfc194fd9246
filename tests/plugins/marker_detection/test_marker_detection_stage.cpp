// The marker_detection stage in a pipeline, fed by the simulator's rendered
// frames or by one camera's image, and its parameters.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/marker_set.hpp"

using namespace touchcloud;

namespace {

class MarkerDetectionStage : public touchcloud::test::PipelineFixture {
 protected:
  RunResult run(const std::string& detect_params) {
    write("object: {analytic: plane, height_mm: 10}\neffects: [refraction, render, pixel_noise, blur]\n",
          "scene.yaml");
    Pipeline p = load(
        "stages:\n"
        "  - id: sim\n"
        "    plugin: marker_gelstereo_simulator\n"
        "    params: {scene: scene.yaml, target_xy_mm: [0, 0]}\n"
        "  - id: detect\n"
        "    plugin: marker_detection\n"
        "    params: {" + detect_params + "}\n"
        "    inputs: {frame: sim.frame}\n");
    RunOptions o;
    o.quiet = true;
    return run_pipeline(p, o);
  }
};

}  // namespace

TEST_F(MarkerDetectionStage, FindsTheRenderedMarkersInBothViews) {
  const RunResult r = run("polarity: dark, diameter_px: [3, 12], contrast_grey: 30");
  const double left = r.record.metrics.at("detect.markers_left").values.at(0);
  const double right = r.record.metrics.at("detect.markers_right").values.at(0);
  EXPECT_GT(left, 1000);
  EXPECT_GT(right, 1000);
  // Looking for bright dots instead finds only a few pockets of gel between them.
  const RunResult bright = run("polarity: bright");
  EXPECT_LT(bright.record.metrics.at("detect.markers_left").values.at(0), 0.05 * left);
}

TEST_F(MarkerDetectionStage, ParametersAreChecked) {
  try {
    run("diameter_px: [12, 3]");
    ADD_FAILURE() << "ran with diameter_px [12, 3]";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("diameter_px"), std::string::npos) << e.what();
  }
  const auto d = errors(
      "stages:\n  - id: detect\n    plugin: marker_detection\n    params: {polarity: grey}\n");
  ASSERT_FALSE(d.empty());
  EXPECT_TRUE(touchcloud::test::mentions(d[0], "polarity")) << d[0].str();
}

namespace {

// A grey image with three dark dots of radius 4 in a row, at x = 20, 45, 70.
cv::Mat three_dots() {
  cv::Mat image(60, 100, CV_8UC1, cv::Scalar(200));
  for (int x : {20, 45, 70}) cv::circle(image, {x, 30}, 4, cv::Scalar(40), cv::FILLED);
  return image;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

MarkerSetPtr detect_one_camera(CameraView view, test::StageHarness& stage) {
  auto image = std::make_shared<CameraImage>();
  image->image = three_dots();
  image->view = view;
  image->timestamp_s = 0.5;
  return stage.process_one<MarkerSetPtr>({{"image", std::any(CameraImagePtr(image))}}, "markers");
}

}  // namespace

TEST(MarkerDetectionOneCamera, AnImagesMarkersAreInItsViewOnly) {
  test::StageHarness stage("marker_detection", {}, "detect");
  stage.configure();
  const MarkerSetPtr mono = detect_one_camera(CameraView::Mono, stage);
  ASSERT_EQ(mono->views, std::vector<CameraView>{CameraView::Mono});
  EXPECT_FALSE(mono->stereo());
  ASSERT_EQ(mono->mono.size(), 3u);
  EXPECT_TRUE(mono->left.empty());
  EXPECT_TRUE(mono->right.empty());
  EXPECT_LT((mono->mono[1].centre_px - Eigen::Vector2d(45, 30)).norm(), 0.05);
  EXPECT_EQ(mono->timestamp_s, 0.5);
  EXPECT_EQ(stage.metric("markers_mono"), 3);
  // One camera of a stereo sensor, read alone: its own view's list.
  const MarkerSetPtr right = detect_one_camera(CameraView::Right, stage);
  ASSERT_EQ(right->views, std::vector<CameraView>{CameraView::Right});
  EXPECT_EQ(right->right.size(), 3u);
  EXPECT_TRUE(right->mono.empty());
  EXPECT_EQ(stage.metric("markers_right"), 3);
}

TEST(MarkerDetectionOneCamera, BadImagesAreRefusedNamingTheInput) {
  test::StageHarness stage("marker_detection", {}, "detect");
  stage.configure();
  auto refused = [&](CameraImagePtr image) -> std::string {
    try {
      stage.process({{"image", std::any(image)}}, {"markers"});
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_TRUE(contains(refused(nullptr), "input 'image': no camera image"));
  auto empty = std::make_shared<CameraImage>();
  EXPECT_TRUE(contains(refused(empty), "input 'image' is empty"));
  auto u16 = std::make_shared<CameraImage>();
  u16->image = cv::Mat(20, 20, CV_16UC1, cv::Scalar(0));
  EXPECT_TRUE(contains(refused(u16), "input 'image' is CV_16UC1"));
}

TEST_F(MarkerDetectionStage, ExactlyOneOfFrameAndImageIsWired) {
  auto none = errors("stages:\n  - id: detect\n    plugin: marker_detection\n");
  ASSERT_EQ(none.size(), 1u);
  EXPECT_TRUE(test::mentions(none[0], "is missing its images: wire one of its inputs 'frame' or 'image' or 'colour'"))
      << none[0].str();
  EXPECT_EQ(none[0].where.line, 2);
  cv::imwrite((dir_ / "dots.png").string(), three_dots());
  write("object: {analytic: plane, height_mm: 10}\neffects: [refraction, render]\n", "scene.yaml");
  auto both = errors(
      "stages:\n"
      "  - id: sim\n    plugin: marker_gelstereo_simulator\n    params: {scene: scene.yaml, target_xy_mm: [0, 0]}\n"
      "  - id: read\n    plugin: image_reader\n    params: {path: dots.png}\n"
      "  - id: detect\n    plugin: marker_detection\n    inputs: {frame: sim.frame, image: read.image}\n");
  ASSERT_EQ(both.size(), 1u);
  EXPECT_TRUE(test::mentions(both[0], "takes one of its inputs 'frame' or 'image' or 'colour' (its images), but "
                                      "'frame' and 'image' are wired"))
      << both[0].str();
}

TEST_F(MarkerDetectionStage, BorderAndMinQualityAreChecked) {
  const std::string head = "stages:\n  - id: read\n    plugin: image_reader\n    params: {path: dots.png}\n"
                           "  - id: detect\n    plugin: marker_detection\n    inputs: {image: read.image}\n";
  cv::imwrite((dir_ / "dots.png").string(), three_dots());
  auto border = errors(head + "    params: {border: trim}\n");
  ASSERT_EQ(border.size(), 1u);
  EXPECT_TRUE(test::mentions(border[0], "must be one of: keep, drop")) << border[0].str();
  auto quality = errors(head + "    params: {min_quality: 1.5}\n");
  ASSERT_EQ(quality.size(), 1u);
  EXPECT_TRUE(test::mentions(quality[0], "'min_quality'")) << quality[0].str();
  EXPECT_TRUE(test::mentions(quality[0], "in [0, 1]")) << quality[0].str();
}
