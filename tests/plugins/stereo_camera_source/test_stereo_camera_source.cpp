// stereo_camera_source: simulated colour-pattern GelStereo presses as two
// video files, one side-by-side video and two cameras' image files with
// index.csv timestamps stream through the dense chain (contact mask, SGBM,
// cloud) to the clouds a run of the same chain on the pairs' image files
// gives, bit for bit.
#include <opencv2/imgcodecs.hpp>

#include "pipeline_fixture.hpp"
#include "stream_results.hpp"
#include "stereo_presses.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/stereo_frame.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

const std::string kSensor = (source_dir() / "sample_clouds/colour_recording/sensor.yaml").string();

// The colour-pattern chain after the source (pipelines/dense_from_recordings.yaml's):
// both pairs rectified, contact mask against the reference, SGBM
// disparity, cloud through the plate, one file per pair.
std::string dense_chain(const std::string& frame, const std::string& reference) {
  return "        - id: rectify\n"
         "          plugin: stereo_rectification\n"
         "          params: {sensor: " + kSensor + ", zero_disparity: true}\n"
         "          inputs: {frame: " + frame + "}\n"
         "        - id: rectify_reference\n"
         "          plugin: stereo_rectification\n"
         "          params: {sensor: " + kSensor + ", zero_disparity: true}\n"
         "          inputs: {frame: " + reference + "}\n"
         "        - id: mask\n"
         "          plugin: contact_mask\n"
         "          params: {threshold_grey: 30}\n"
         "          inputs: {frame: rectify.frame, reference: rectify_reference.frame}\n"
         "        - id: disparity\n"
         "          plugin: stereo_disparity\n"
         "          params: {method: sgbm, block_size_px: 7, min_disparity_px: 64, num_disparities: 192}\n"
         "          inputs: {frame: rectify.frame}\n"
         "        - id: cloud\n"
         "          plugin: disparity_to_cloud\n"
         "          params: {sensor: " + kSensor + ", refraction: true}\n"
         "          inputs: {disparity: disparity.disparity, mask: mask.mask}\n"
         "        - id: write\n"
         "          plugin: cloud_writer\n"
         "          params: {path: 'cloud_{iteration}.pcd'}\n"
         "          inputs: {cloud: cloud.cloud}\n";
}

class StereoCameraSource : public PipelineFixture {
 protected:
  void SetUp() override { pairs_ = stereo_presses(); }

  RunResult stream(const std::string& source_params, const fs::path& out) {
    Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
                      "      stages:\n        - id: cam\n          plugin: stereo_camera_source\n"
                      "          params: {colour: true, " + source_params + "}\n" +
                      dense_chain("cam.frame", "cam.reference"));
    RunOptions o;
    o.quiet = true;
    o.out_dir = out;
    return run_pipeline(p, o);
  }
  // The same chain run on the pairs as image files (stereo_image_reader):
  // the first pair the reference, the others one per iteration.
  std::vector<std::string> run_on_image_files() {
    const fs::path files = dir_ / "pairs";
    fs::create_directories(files);
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      const std::string name = k == 0 ? "rest" : std::to_string(k - 1);
      cv::imwrite((files / ("left_" + name + ".png")).string(), pairs_[k].left);
      cv::imwrite((files / ("right_" + name + ".png")).string(), pairs_[k].right);
    }
    Pipeline p = load("stages:\n  - id: rest\n    plugin: stereo_image_reader\n"
                      "    params: {left: pairs/left_rest.png, right: pairs/right_rest.png, colour: true}\n"
                      "  - id: frames\n    loop:\n      max_iterations: " + std::to_string(pairs_.size() - 1) + "\n"
                      "      stages:\n        - id: read\n          plugin: stereo_image_reader\n"
                      "          params: {left: 'pairs/left_{iteration}.png', right: 'pairs/right_{iteration}.png', "
                      "colour: true}\n" +
                      dense_chain("read.frame", "rest.frame"));
    RunOptions o;
    o.quiet = true;
    o.out_dir = dir_ / "from_files";
    run_pipeline(p, o);
    return clouds(dir_ / "from_files");
  }
  std::vector<ViewPair> pairs_;
};

}  // namespace

TEST_F(StereoCameraSource, TwoLosslessVideosGiveTheCloudsOfTheirImageFilesBitForBit) {
  const std::vector<std::string> expected = run_on_image_files();
  ASSERT_EQ(expected.size(), pairs_.size() - 1);
  EXPECT_NE(expected[1], expected[0]);  // the moved press is another cloud
  write_video(dir_ / "left.mkv", lefts(pairs_), 30);
  write_video(dir_ / "right.mkv", rights(pairs_), 30);
  const RunResult r = stream("left_video: left.mkv, right_video: right.mkv", dir_ / "videos");
  EXPECT_EQ(clouds(dir_ / "videos"), expected);
  EXPECT_EQ(metric(r, "cam.frames_processed"), static_cast<double>(pairs_.size() - 1));
  EXPECT_EQ(metric(r, "cam.pairs_refused"), 0.0);
  EXPECT_EQ(metric(r, "cam.frames_dropped"), 0.0);
  EXPECT_EQ(metric(r, "cam.pair_skew_max_ms"), 0.0);
  EXPECT_EQ(metric(r, "cam.frames_captured"), 2.0 * static_cast<double>(pairs_.size()));
}

TEST_F(StereoCameraSource, ASideBySideVideoGivesTheCloudsOfItsImageFilesBitForBit) {
  const std::vector<std::string> expected = run_on_image_files();
  write_video(dir_ / "both.mkv", side_by_side(pairs_), 30);
  const RunResult r = stream("video: both.mkv", dir_ / "side_by_side");
  EXPECT_EQ(clouds(dir_ / "side_by_side"), expected);
  EXPECT_EQ(metric(r, "cam.frames_processed"), static_cast<double>(pairs_.size() - 1));
  EXPECT_EQ(metric(r, "cam.frames_captured"), static_cast<double>(pairs_.size()));
}

TEST_F(StereoCameraSource, TwoCamerasImageFilesPairedByTheirTimestampsGiveTheSameClouds) {
  const std::vector<std::string> expected = run_on_image_files();
  // Two clocks that differ by a few ms at every frame: within max_skew_ms.
  write_side(dir_ / "rec", "left", lefts(pairs_), {100.0, 100.033, 100.067, 100.1});
  write_side(dir_ / "rec", "right", rights(pairs_), {100.004, 100.036, 100.063, 100.102});
  Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
                    "      stages:\n        - id: cam\n          plugin: stereo_camera_source\n"
                    "          params: {colour: true, left_frames: rec/left.csv, right_frames: rec/right.csv}\n" +
                    dense_chain("cam.frame", "cam.reference"));
  RunOptions o;
  o.quiet = true;
  o.out_dir = dir_ / "files";
  o.capture = {"cam.stamp", "cam.frame"};
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(clouds(dir_ / "files"), expected);
  EXPECT_EQ(metric(r, "cam.pairs_refused"), 0.0);
  EXPECT_NEAR(metric(r, "cam.pair_skew_max_ms"), 4.0, 1e-6);
  // The pair carries the left camera's frame number and time since its first frame.
  const auto stamp = std::any_cast<FrameStamp>(r.captured.at("cam.stamp"));
  EXPECT_EQ(stamp.sequence, 3);
  EXPECT_NEAR(stamp.timestamp_s, 0.1, 1e-9);
  const auto frame = std::any_cast<StereoFramePtr>(r.captured.at("cam.frame"));
  EXPECT_EQ(frame->index, 3);
  EXPECT_EQ(frame->left.type(), CV_8UC3);
}

TEST_F(StereoCameraSource, GreyPairsForTheMarkerSensor) {
  write_video(dir_ / "both.mkv", side_by_side(pairs_), 30);
  Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
                    "      stages:\n        - id: cam\n          plugin: stereo_camera_source\n"
                    "          params: {video: both.mkv, reference_frames: 0}\n");
  RunOptions o;
  o.quiet = true;
  o.capture = {"cam.frame"};
  const RunResult r = run_pipeline(p, o);
  const auto frame = std::any_cast<StereoFramePtr>(r.captured.at("cam.frame"));
  EXPECT_EQ(frame->left.type(), CV_8UC1);
  EXPECT_EQ(frame->left.size(), cv::Size(640, 360));
  EXPECT_EQ(frame->right.size(), cv::Size(640, 360));
  EXPECT_EQ(metric(r, "cam.frames_processed"), static_cast<double>(pairs_.size()));  // no reference taken
}
