// image_reader's sequences and colour: a glob walks its files in natural
// order, a numbered sequence ends its loop cleanly through `last` (what was
// read is kept), `validate` refuses a pattern that matches nothing or lacks
// a frame, and the colour output refuses a grey or a 16-bit file naming it.
#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

namespace {

cv::Mat row_of_dots(int dots) {
  cv::Mat image(80, 120, CV_8UC1, cv::Scalar(200));
  for (int i = 0; i < dots; ++i) cv::circle(image, {20 + 25 * i, 40}, 4, cv::Scalar(40), cv::FILLED);
  return image;
}

class ImageSequenceRun : public touchcloud::test::PipelineFixture {
 protected:
  std::string pipeline(const std::string& reader_params, int iterations) {
    return "stages:\n"
           "  - id: frames\n"
           "    loop:\n"
           "      max_iterations: " + std::to_string(iterations) + "\n"
           "      until: read.last\n"
           "      stages:\n"
           "        - id: read\n"
           "          plugin: image_reader\n"
           "          params: {" + reader_params + "}\n"
           "        - id: detect\n"
           "          plugin: marker_detection\n"
           "          inputs: {image: read.image}\n";
  }
  RunResult run(const std::string& reader_params, int iterations) {
    Pipeline p = load(pipeline(reader_params, iterations));
    RunOptions o;
    o.quiet = true;
    return run_pipeline(p, o);
  }
  void save(const std::string& name, const cv::Mat& image) { ASSERT_TRUE(cv::imwrite((dir_ / name).string(), image)); }
  std::string only_error(const std::string& reader_params) {
    const auto d = errors(pipeline(reader_params, 10));
    return d.size() == 1 ? d[0].str() : "(" + std::to_string(d.size()) + " errors)";
  }
};

}  // namespace

TEST_F(ImageSequenceRun, ANumberedSequenceEndsItsLoopCleanlyOnItsLastFile) {
  for (int i = 0; i < 3; ++i) save("gel_" + std::to_string(i) + ".png", row_of_dots(i + 1));
  const RunResult r = run("path: 'gel_{iteration}.png'", 10);
  EXPECT_EQ(r.record.metrics.at("detect.markers_mono").values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(r.record.metrics.at("read.frames_read").values, (std::vector<double>{1, 2, 3}));
}

TEST_F(ImageSequenceRun, AGlobWalksItsFilesInNaturalOrder) {
  save("frame_2.png", row_of_dots(1));
  save("frame_10.png", row_of_dots(3));
  save("frame_7.png", row_of_dots(2));
  save("notes_1.png", row_of_dots(4));  // not matched
  const RunResult r = run("path: 'frame_*.png'", 10);
  EXPECT_EQ(r.record.metrics.at("detect.markers_mono").values, (std::vector<double>{1, 2, 3}));
}

TEST_F(ImageSequenceRun, ValidateRefusesAPatternThatMatchesNothingOrLacksAFrame) {
  save("gel_0.png", row_of_dots(1));
  save("gel_1.png", row_of_dots(1));
  save("gel_3.png", row_of_dots(1));
  const std::string gap = only_error("path: 'gel_{iteration}.png'");
  EXPECT_NE(gap.find("parameter 'path'"), std::string::npos) << gap;
  EXPECT_NE(gap.find("frame 2 (gel_2.png) is missing; the files run from frame 0 to 3"), std::string::npos) << gap;
  const std::string none = only_error("path: 'press_{iteration}.png'");
  EXPECT_NE(none.find("press_{iteration}.png: no file matches the pattern"), std::string::npos) << none;
  const std::string glob = only_error("path: 'press_*.png'");
  EXPECT_NE(glob.find("no file matches 'press_*.png'"), std::string::npos) << glob;
  save("press_1.png", row_of_dots(1));  // no frame 0
  const std::string first = only_error("path: 'press_{iteration}.png'");
  EXPECT_NE(first.find("frame 0 (press_0.png) is missing"), std::string::npos) << first;
}

TEST_F(ImageSequenceRun, ALoopLongerThanTheSequenceWithoutUntilIsRefusedNamingIt) {
  for (int i = 0; i < 2; ++i) save("gel_" + std::to_string(i) + ".png", row_of_dots(1));
  Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 3\n      stages:\n"
                    "        - id: read\n          plugin: image_reader\n          params: {path: 'gel_*.png'}\n"
                    "        - id: detect\n          plugin: marker_detection\n          inputs: {image: read.image}\n");
  RunOptions o;
  o.quiet = true;
  try {
    run_pipeline(p, o);
    ADD_FAILURE() << "ran past the sequence";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has 2 files; file 3 was asked for"), std::string::npos) << e.what();
  }
}

namespace {

std::string colour_error(const std::filesystem::path& file) {
  test::StageHarness reader("image_reader", {{"path", file.string()}});
  reader.configure();
  try {
    reader.process_one<MonoColourFramePtr>({}, "colour");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST(ImageReaderColour, ReadsEightBitColourWithTheSensorsNameAndPitch) {
  test::TempDir dir;
  cv::Mat bgr(48, 64, CV_8UC3), bgra;
  cv::RNG(47).fill(bgr, cv::RNG::UNIFORM, 0, 256);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  ASSERT_TRUE(cv::imwrite((dir / "gel.png").string(), bgr));
  ASSERT_TRUE(cv::imwrite((dir / "gel_alpha.png").string(), bgra));
  for (const char* name : {"gel.png", "gel_alpha.png"}) {
    test::StageHarness reader("image_reader",
                              {{"path", (dir / name).string()}, {"sensor", std::string("mini")}, {"mm_per_px", 0.0625}});
    reader.configure();
    const auto frame = reader.process_one<MonoColourFramePtr>({}, "colour");
    ASSERT_EQ(frame->image.type(), CV_8UC3) << name;
    EXPECT_EQ(cv::norm(frame->image, bgr, cv::NORM_INF), 0) << name;
    EXPECT_EQ(frame->sensor, "mini");
    EXPECT_EQ(frame->mm_per_px, 0.0625);
  }
}

TEST(ImageReaderColour, TheStampNamesEachFileOfAGlob) {
  test::TempDir dir;
  const cv::Mat bgr(24, 32, CV_8UC3, cv::Scalar(10, 20, 30));
  for (const char* name : {"press_10.png", "press_9.png"}) ASSERT_TRUE(cv::imwrite((dir / name).string(), bgr));
  test::StageHarness reader("image_reader", {{"path", (dir / "press_*.png").string()}});
  reader.configure();
  for (const auto& [sequence, name] : {std::pair{0, "press_9.png"}, std::pair{1, "press_10.png"}}) {
    const auto stamp = reader.process_one<FrameStamp>({}, "stamp");
    EXPECT_EQ(stamp.sequence, sequence);
    EXPECT_EQ(stamp.source, name);
  }
}

TEST(ImageReaderColour, AGreyOrSixteenBitFileIsRefusedNamingIt) {
  test::TempDir dir;
  ASSERT_TRUE(cv::imwrite((dir / "grey.png").string(), row_of_dots(2)));
  const std::string grey = colour_error(dir / "grey.png");
  EXPECT_NE(grey.find((dir / "grey.png").string() + " is a grey image; a colour (BGR) image is needed"), std::string::npos)
      << grey;
  cv::Mat deep(48, 64, CV_16UC3, cv::Scalar(1000, 20000, 40000));
  ASSERT_TRUE(cv::imwrite((dir / "deep.png").string(), deep));
  const std::string sixteen = colour_error(dir / "deep.png");
  EXPECT_NE(sixteen.find((dir / "deep.png").string() + " holds 16-bit samples; an 8-bit colour image is needed"),
            std::string::npos)
      << sixteen;
}
