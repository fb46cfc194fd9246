// stereo_image_reader: image files into a stereo frame, '{iteration}' in the
// paths, and unreadable or mismatched files refused naming the file.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/plugin_registry.hpp"
#include "touchcloud/types/stereo_frame.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

namespace {

// A grey image with `dots` dark dots in a row.
cv::Mat dots_image(int dots, cv::Size size = {120, 80}) {
  cv::Mat image(size, CV_8UC1, cv::Scalar(200));
  for (int i = 0; i < dots; ++i) cv::circle(image, {20 + 25 * i, 40}, 4, cv::Scalar(40), cv::FILLED);
  return image;
}

class StereoImageReader : public touchcloud::test::PipelineFixture {
 protected:
  std::string pipeline(const std::string& left, const std::string& right) {
    return "stages:\n"
           "  - id: read\n"
           "    plugin: stereo_image_reader\n"
           "    params: {left: " + left + ", right: " + right + "}\n"
           "  - id: detect\n"
           "    plugin: marker_detection\n"
           "    inputs: {frame: read.frame}\n";
  }
  void save(const std::string& name, const cv::Mat& image) { ASSERT_TRUE(cv::imwrite((dir_ / name).string(), image)); }
};

}  // namespace

TEST_F(StereoImageReader, ReadsBothImagesRelativeToThePipelineFile) {
  save("left.png", dots_image(3));
  save("right.png", dots_image(2));
  Pipeline p = load(pipeline("left.png", "right.png"));
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(r.record.metrics.at("detect.markers_left").values.at(0), 3);
  EXPECT_EQ(r.record.metrics.at("detect.markers_right").values.at(0), 2);
}

TEST_F(StereoImageReader, UnreadableAndMismatchedFilesAreRefusedNamingTheFile) {
  save("left.png", dots_image(3));
  touchcloud::test::write_file(dir_ / "broken.png", "not an image");
  auto d = errors(pipeline("left.png", "broken.png"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "parameter 'right'")) << d[0].str();
  EXPECT_TRUE(mentions(d[0], "broken.png cannot be read")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 4);

  save("small.png", dots_image(1, {60, 80}));
  d = errors(pipeline("left.png", "small.png"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "small.png is 60 x 80 px but the left image")) << d[0].str();

  d = errors(pipeline("left.png", "missing.png"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "missing.png does not exist")) << d[0].str();
}

TEST_F(StereoImageReader, IterationInThePathWalksThroughARecordedSequence) {
  for (int i = 0; i < 3; ++i) {
    save("left_" + std::to_string(i) + ".png", dots_image(i + 1));
    save("right_" + std::to_string(i) + ".png", dots_image(1));
  }
  const std::string loop = "stages:\n"
                           "  - id: frames\n"
                           "    loop:\n"
                           "      max_iterations: 3\n"
                           "      stages:\n"
                           "        - {id: read, plugin: stereo_image_reader,\n"
                           "           params: {left: 'left_{iteration}.png', right: 'right_{iteration}.png', fps: 10}}\n"
                           "        - {id: detect, plugin: marker_detection, inputs: {frame: read.frame}}\n";
  RunOptions o;
  o.quiet = true;
  Pipeline p = load(loop);
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(r.record.metrics.at("detect.markers_left").values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(r.record.metrics.at("detect.markers_right").values, (std::vector<double>{1, 1, 1}));

  // One iteration too many: the missing file is named when the loop gets there.
  Pipeline four = load(loop.substr(0, loop.find("max_iterations: 3")) + "max_iterations: 4" +
                       loop.substr(loop.find("max_iterations: 3") + 17));
  try {
    run_pipeline(four, o);
    ADD_FAILURE() << "read a missing file";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("left_3.png cannot be read"), std::string::npos) << e.what();
  }
  // A pattern in a folder that does not exist is found before the run.
  const auto d = errors("stages:\n  - {id: read, plugin: stereo_image_reader,\n"
                        "     params: {left: 'nowhere/l_{iteration}.png', right: r.png}}\n");
  ASSERT_FALSE(d.empty());
  EXPECT_TRUE(mentions(d[0], "nowhere does not exist")) << d[0].str();
}

TEST_F(StereoImageReader, ColourReadsBgrAndGreyStaysTheDefault) {
  cv::Mat bgr(80, 120, CV_8UC3, cv::Scalar(10, 20, 200));  // a red pair
  save("left.png", bgr);
  save("right.png", bgr);
  touchcloud::test::StageHarness grey("stereo_image_reader",
                                      {{"left", (dir_ / "left.png").string()}, {"right", (dir_ / "right.png").string()}});
  grey.configure();
  EXPECT_EQ(grey.process_one<StereoFramePtr>({}, "frame")->left.type(), CV_8UC1);
  touchcloud::test::StageHarness colour("stereo_image_reader", {{"left", (dir_ / "left.png").string()},
                                                                {"right", (dir_ / "right.png").string()},
                                                                {"colour", true}});
  colour.configure();
  const auto frame = colour.process_one<StereoFramePtr>({}, "frame");
  ASSERT_EQ(frame->right.type(), CV_8UC3);
  EXPECT_EQ(frame->right.at<cv::Vec3b>(40, 60), cv::Vec3b(10, 20, 200));
}

// A colour-pattern pair saved as grey (or as 16-bit) has lost its pattern:
// refused naming the file, not turned into three equal channels.
TEST_F(StereoImageReader, AGreyOr16BitFileIsRefusedWhereColourIsNeeded) {
  save("left.png", cv::Mat(80, 120, CV_8UC3, cv::Scalar(10, 20, 200)));
  save("grey.png", dots_image(3));
  save("deep.png", cv::Mat(80, 120, CV_16UC3, cv::Scalar(1000, 2000, 3000)));
  for (const char* right : {"grey.png", "deep.png"}) {
    const auto d = errors("stages:\n  - id: read\n    plugin: stereo_image_reader\n"
                          "    params: {left: left.png, right: " + std::string(right) + ", colour: true}\n");
    ASSERT_EQ(d.size(), 1u) << right;
    EXPECT_TRUE(mentions(d[0], "the right image " + (dir_ / right).string())) << d[0].str();
    EXPECT_TRUE(mentions(d[0], std::string(right) == "grey.png" ? "is a grey image; a colour (BGR) image is needed"
                                                                 : "16-bit samples"))
        << d[0].str();
  }
}

// OpenCV decodes a JPEG cut short with its missing part grey (and libjpeg
// prints "Premature end of JPEG file"): refused, naming the file.
TEST_F(StereoImageReader, AJpegCutShortIsRefusedNamingTheFile) {
  save("left.png", dots_image(3));
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", dots_image(3), jpeg));
  touchcloud::test::write_file(dir_ / "right.jpg", std::string(jpeg.begin(), jpeg.begin() + jpeg.size() / 2));
  testing::internal::CaptureStderr();
  const auto d = errors(pipeline("left.png", "right.jpg"));
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "the right image " + (dir_ / "right.jpg").string() +
                                 " cannot be read: not a whole JPEG: libjpeg says \"Premature end of JPEG file\""))
      << d[0].str();
}
