// stereo_camera_source's recording and shaping: `record` keeps both
// cameras' frames with their clocks, and the recording replays through the
// source itself to the same pairs bit for bit; `crop` and `resize` give the
// sizes asked, for two cameras and for a side-by-side camera (cut after
// shaping), also from a sensor file's camera: section; a crop outside the
// frame is refused at validation, naming the camera and the crop.
#include <fstream>

#include <opencv2/core.hpp>

#include "pipeline_fixture.hpp"
#include "stereo_presses.hpp"
#include "touchcloud/types/stereo_frame.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

class StereoRecording : public PipelineFixture {
 protected:
  void SetUp() override { pairs_ = stereo_presses(); }
  static std::string source_stage(const std::string& params) {
    return "stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
           "      stages:\n        - id: cam\n          plugin: stereo_camera_source\n          params: {" + params + "}\n";
  }
  // Every pair the source hands on, in order.
  std::vector<StereoFramePtr> pairs(const std::string& params) {
    Pipeline p = load(source_stage(params));
    RunOptions o;
    o.quiet = true;
    o.out_dir = dir_ / "out";
    o.capture = {"cam.frame"};
    o.capture_every_call = true;
    const RunResult r = run_pipeline(p, o);
    std::vector<StereoFramePtr> out;
    for (const auto& v : r.captured_every_call.at("cam.frame")) out.push_back(std::any_cast<StereoFramePtr>(v));
    return out;
  }
  std::string load_error(const std::string& params) {
    const auto d = errors(source_stage(params));
    if (d.size() != 1) return "expected one diagnostic, got " + std::to_string(d.size());
    return d[0].message;
  }
  static bool same(const cv::Mat& a, const cv::Mat& b) {
    return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
  }

  std::vector<ViewPair> pairs_;
};

}  // namespace

TEST_F(StereoRecording, TwoCamerasRecordingReplaysToTheSamePairsBitForBit) {
  write_video(dir_ / "left.mkv", lefts(pairs_), 30);
  write_video(dir_ / "right.mkv", rights(pairs_), 30);
  const std::string rec = (dir_ / "rec").string();
  const auto live = pairs("left_video: left.mkv, right_video: right.mkv, colour: true, record: " + rec);
  ASSERT_EQ(live.size(), pairs_.size() - 1);  // the first pair is the reference
  // Both cameras' frames, the reference pair's too, each with its row.
  for (const char* side : {"left", "right"}) {
    std::ifstream index(dir_ / "rec" / side / "index.csv");
    std::string line;
    int rows = -1;  // the header
    while (std::getline(index, line)) ++rows;
    EXPECT_EQ(rows, static_cast<int>(pairs_.size())) << side;
  }
  const auto replayed = pairs("left_frames: " + rec + "/left/index.csv, right_frames: " + rec +
                              "/right/index.csv, colour: true");
  ASSERT_EQ(replayed.size(), live.size());
  for (std::size_t k = 0; k < live.size(); ++k) {
    EXPECT_TRUE(same(replayed[k]->left, live[k]->left)) << k;
    EXPECT_TRUE(same(replayed[k]->right, live[k]->right)) << k;
    EXPECT_NEAR(replayed[k]->timestamp_s, live[k]->timestamp_s, 1e-9) << k;
  }
  // A second recording into the same folder is refused before anything runs.
  EXPECT_NE(load_error("left_video: left.mkv, right_video: right.mkv, record: " + rec).find("already holds a recording"),
            std::string::npos);
}

TEST_F(StereoRecording, CropAndResizeGiveTheSizesAsked) {
  write_video(dir_ / "left.mkv", lefts(pairs_), 30);
  write_video(dir_ / "right.mkv", rights(pairs_), 30);
  const auto two = pairs("left_video: left.mkv, right_video: right.mkv, crop: [40, 20, 560, 320], resize: [280, 160]");
  ASSERT_FALSE(two.empty());
  EXPECT_EQ(two[0]->left.size(), cv::Size(280, 160));
  EXPECT_EQ(two[0]->right.size(), cv::Size(280, 160));
  // A side-by-side camera (1280 x 360) is shaped whole, then cut at its middle.
  write_video(dir_ / "both.mkv", side_by_side(pairs_), 30);
  const auto both = pairs("video: both.mkv, crop: [0, 0, 1280, 300], resize: [640, 150]");
  ASSERT_FALSE(both.empty());
  EXPECT_EQ(both[0]->left.size(), cv::Size(320, 150));
  EXPECT_EQ(both[0]->right.size(), cv::Size(320, 150));
  // The same from a sensor file's camera: section; the stage's own resize wins.
  write_file(dir_ / "sensor.yaml", "camera:\n  size: [640, 360]\n  crop: [40, 20, 560, 320]\n  resize: [280, 160]\n");
  const auto preset = pairs("left_video: left.mkv, right_video: right.mkv, preset: sensor.yaml, resize: [140, 80]");
  ASSERT_FALSE(preset.empty());
  EXPECT_EQ(preset[0]->left.size(), cv::Size(140, 80));
}

TEST_F(StereoRecording, ACropOutsideTheFrameIsRefusedNamingTheCameraAndTheCrop) {
  write_video(dir_ / "left.mkv", lefts(pairs_), 30);
  write_video(dir_ / "right.mkv", rights(pairs_), 30);
  const std::string e = load_error("left_video: left.mkv, right_video: right.mkv, crop: [600, 0, 100, 100]");
  EXPECT_NE(e.find("parameter 'left_video'"), std::string::npos) << e;
  EXPECT_NE(e.find("crop [600, 0, 100, 100] does not fit"), std::string::npos) << e;
  EXPECT_NE(e.find("640 x 360 px"), std::string::npos) << e;
}
