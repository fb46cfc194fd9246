// image_reader: one image file into a camera image with its view, through
// marker_detection; '{iteration}' in the path; unreadable files refused
// naming the file.
#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline_fixture.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

namespace {

// A grey image with `dots` dark dots in a row.
cv::Mat dots_image(int dots) {
  cv::Mat image(80, 120, CV_8UC1, cv::Scalar(200));
  for (int i = 0; i < dots; ++i) cv::circle(image, {20 + 25 * i, 40}, 4, cv::Scalar(40), cv::FILLED);
  return image;
}

class ImageReader : public touchcloud::test::PipelineFixture {
 protected:
  RunResult run(const std::string& reader_params, int iterations = 1) {
    Pipeline p = load("stages:\n"
                      "  - id: frames\n"
                      "    loop:\n"
                      "      max_iterations: " + std::to_string(iterations) + "\n"
                      "      stages:\n"
                      "        - id: read\n"
                      "          plugin: image_reader\n"
                      "          params: {" + reader_params + "}\n"
                      "        - id: detect\n"
                      "          plugin: marker_detection\n"
                      "          inputs: {image: read.image}\n");
    RunOptions o;
    o.quiet = true;
    return run_pipeline(p, o);
  }
  void save(const std::string& name, const cv::Mat& image) { ASSERT_TRUE(cv::imwrite((dir_ / name).string(), image)); }
};

}  // namespace

TEST_F(ImageReader, ReadsTheImageRelativeToThePipelineFileAsItsView) {
  save("gel.png", dots_image(3));
  const RunResult mono = run("path: gel.png");
  EXPECT_EQ(mono.record.metrics.at("detect.markers_mono").values, std::vector<double>{3});
  EXPECT_EQ(mono.record.metrics.count("detect.markers_left"), 0u);
  const RunResult left = run("path: gel.png, view: left");
  EXPECT_EQ(left.record.metrics.at("detect.markers_left").values, std::vector<double>{3});
}

TEST_F(ImageReader, IterationInThePathWalksASequence) {
  for (int i = 0; i < 3; ++i) save("gel_" + std::to_string(i) + ".png", dots_image(i + 1));
  const RunResult r = run("path: 'gel_{iteration}.png'", 3);
  EXPECT_EQ(r.record.metrics.at("detect.markers_mono").values, (std::vector<double>{1, 2, 3}));
}

TEST_F(ImageReader, AnUnreadableFileIsNamedAtValidation) {
  touchcloud::test::write_file(dir_ / "notes.png", "not an image");
  const auto d = errors("stages:\n  - id: read\n    plugin: image_reader\n    params: {path: notes.png}\n"
                        "  - id: detect\n    plugin: marker_detection\n    inputs: {image: read.image}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "parameter 'path'")) << d[0].str();
  EXPECT_TRUE(mentions(d[0], "notes.png cannot be read")) << d[0].str();
  const auto view = errors("stages:\n  - id: read\n    plugin: image_reader\n    params: {path: notes.png, view: "
                           "top}\n");
  ASSERT_FALSE(view.empty());
  EXPECT_TRUE(std::any_of(view.begin(), view.end(),
                          [](const Diagnostic& d) { return mentions(d, "must be one of: mono, left, right"); }));
}
