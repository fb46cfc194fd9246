// camera_source: simulated presses as video files in several codecs and as
// image files through the GelSight-type chain (photometric depth -> cloud)
// and marker detection; the reference from the first frames or a file; a
// preset's camera section and parameters that override it; timestamps from
// an index.csv; frames dropped behind a slow stage, counted.
#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline_fixture.hpp"
#include "press_videos.hpp"
#include "stream_results.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

const std::string kCalibration =
    (source_dir() / "sample_clouds/gelsight_ball/photometric_calibration.yaml").string();

class CameraSource : public PipelineFixture {
 protected:
  void SetUp() override {
    frames_ = press_frames();
    ASSERT_GE(frames_.size(), 5u);
  }
  // The GelSight-type live chain, the source given by `source_params`,
  // writing cloud_K.pcd per frame into `out`.
  RunResult gelsight(const std::string& source_params, const fs::path& out) {
    Pipeline p = load("stages:\n"
                      "  - id: frames\n"
                      "    loop:\n"
                      "      max_iterations: 100\n"
                      "      until: cam.done\n"
                      "      stages:\n"
                      "        - id: cam\n"
                      "          plugin: camera_source\n"
                      "          params: {" + source_params + "}\n"
                      "        - id: depth\n"
                      "          plugin: photometric_depth\n"
                      "          params: {calibration: " + kCalibration + ", border: free}\n"
                      "          inputs: {image: cam.frame, reference: cam.reference}\n"
                      "        - id: cloud\n"
                      "          plugin: height_to_cloud\n"
                      "          params: {points: all, stride_px: 4}\n"
                      "          inputs: {height: depth.height}\n"
                      "        - id: write\n"
                      "          plugin: cloud_writer\n"
                      "          params: {path: 'cloud_{iteration}.pcd'}\n"
                      "          inputs: {cloud: cloud.cloud}\n");
    RunOptions o;
    o.quiet = true;
    o.out_dir = out;
    return run_pipeline(p, o);
  }
  std::vector<cv::Mat> frames_;
};

TEST_F(CameraSource, LosslessVideosGiveTheCloudsOfTheirImageFilesBitForBit) {
  write_frame_files(dir_ / "png", frames_);
  const auto expected = clouds((gelsight("frames: 'png/frame_{iteration}.png'", dir_ / "from_png"), dir_ / "from_png"));
  ASSERT_EQ(expected.size(), frames_.size() - 1);  // the first frame is the reference
  for (const char* codec : {"FFV1:mkv", "HFYU:avi", "MPNG:avi"}) {
    const std::string fourcc = std::string(codec).substr(0, 4), file = "presses_" + fourcc + "." + (codec + 5);
    ASSERT_TRUE(write_video(dir_ / file, fourcc, frames_)) << fourcc;
    const fs::path out = dir_ / ("from_" + fourcc);
    const RunResult r = gelsight("video: " + file, out);
    EXPECT_EQ(clouds(out), expected) << fourcc;
    EXPECT_EQ(metric(r, "cam.frames_processed"), static_cast<double>(frames_.size() - 1));
    EXPECT_EQ(metric(r, "cam.frames_dropped"), 0.0);
  }
}

// A recording keeps every frame as delivered, the reference frame too, so
// replaying it with the same parameters gives the same clouds.
TEST_F(CameraSource, ARecordingReplaysToTheSameCloudsBitForBit) {
  ASSERT_TRUE(write_video(dir_ / "presses.mkv", "FFV1", frames_));
  const std::string rec = (dir_ / "rec").string();
  gelsight("video: presses.mkv, record: " + rec, dir_ / "live");
  const std::string index = read_file(dir_ / "rec" / "index.csv");
  EXPECT_EQ(std::count(index.begin(), index.end(), '\n'), static_cast<long>(frames_.size()) + 1) << index;
  gelsight("frames: rec/index.csv", dir_ / "replay");
  EXPECT_EQ(clouds(dir_ / "replay"), clouds(dir_ / "live"));
  EXPECT_EQ(clouds(dir_ / "live").size(), frames_.size() - 1);
  // A second recording into the same folder is refused before anything runs.
  const auto d = errors("stages:\n  - id: cam\n    plugin: camera_source\n"
                        "    params: {video: presses.mkv, record: " + rec + "}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "already holds a recording")) << d[0].str();
}

// Lossy codecs change pixels by a few grey levels: the heights of a press
// stay within a tenth of the press's depth, the frame count is the same.
TEST_F(CameraSource, LossyVideosGiveCloseHeightsAndEveryFrame) {
  write_frame_files(dir_ / "png", frames_);
  const RunResult exact = gelsight("frames: 'png/frame_{iteration}.png'", dir_ / "from_png");
  const std::vector<double> heights = exact.record.metrics.at("depth.max_height_mm").values;
  for (const char* codec : {"MJPG:avi", "mp4v:mp4"}) {
    const std::string fourcc = std::string(codec).substr(0, 4), file = "presses_" + fourcc + "." + (codec + 5);
    ASSERT_TRUE(write_video(dir_ / file, fourcc, frames_)) << fourcc;
    const RunResult r = gelsight("video: " + file, dir_ / ("from_" + fourcc));
    const std::vector<double>& lossy = r.record.metrics.at("depth.max_height_mm").values;
    ASSERT_EQ(lossy.size(), heights.size()) << fourcc;
    for (std::size_t k = 0; k < heights.size(); ++k)
      EXPECT_NEAR(lossy[k], heights[k], 0.1 * std::max(heights[k], 0.2)) << fourcc << " frame " << k;
  }
}

TEST_F(CameraSource, MarkersDetectedInAVideoAreThoseOfItsImages) {
  std::vector<cv::Mat> markers;
  for (int k = 0; k < 3; ++k)
    markers.push_back(cv::imread((source_dir() / ("sample_clouds/gelsight_markers/markers_" + std::to_string(k) + ".jpg")).string()));
  write_frame_files(dir_ / "png", markers);
  ASSERT_TRUE(write_video(dir_ / "markers.mkv", "FFV1", markers));
  const auto counts = [&](const std::string& source) {
    Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 10\n      until: cam.done\n"
                      "      stages:\n        - id: cam\n          plugin: camera_source\n"
                      "          params: {" + source + ", reference_frames: 0, reference: png/frame_0.png}\n"
                      "        - id: detect\n          plugin: marker_detection\n"
                      "          params: {polarity: dark, diameter_px: [8, 16], contrast_grey: 20, border: keep}\n"
                      "          inputs: {image: cam.image}\n");
    RunOptions o;
    o.quiet = true;
    return run_pipeline(p, o).record.metrics.at("detect.markers_mono").values;
  };
  const std::vector<double> from_files = counts("frames: 'png/frame_{iteration}.png'");
  ASSERT_EQ(from_files.size(), 3u);
  EXPECT_GT(from_files[0], 20.0);
  EXPECT_EQ(counts("video: markers.mkv"), from_files);
}

TEST_F(CameraSource, TheReferenceIsTheMeanOfTheFirstFramesOrAFile) {
  std::vector<cv::Mat> flat = {cv::Mat(24, 32, CV_8UC3, cv::Scalar(10, 20, 30)), cv::Mat(24, 32, CV_8UC3, cv::Scalar(30, 40, 50)),
                               cv::Mat(24, 32, CV_8UC3, cv::Scalar(90, 90, 90))};
  write_frame_files(dir_.path(), flat);
  const auto reference = [&](const std::string& params) {
    Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 10\n      until: cam.done\n"
                      "      stages:\n        - id: cam\n          plugin: camera_source\n"
                      "          params: {frames: 'frame_{iteration}.png', " + params + "}\n");
    RunOptions o;
    o.quiet = true;
    o.capture = {"cam.reference", "cam.stamp"};
    const RunResult r = run_pipeline(p, o);
    const auto ref = std::any_cast<MonoColourFramePtr>(r.captured.at("cam.reference"));
    const auto stamp = std::any_cast<FrameStamp>(r.captured.at("cam.stamp"));
    EXPECT_EQ(stamp.sequence, 2);  // the last frame's number counts those before it
    return std::make_pair(ref->image.at<cv::Vec3b>(0, 0), metric(r, "cam.frames_processed"));
  };
  EXPECT_EQ(reference("reference_frames: 2"), std::make_pair(cv::Vec3b(20, 30, 40), 1.0));
  EXPECT_EQ(reference("reference_frames: 1, warmup_frames: 1"), std::make_pair(cv::Vec3b(30, 40, 50), 1.0));
  cv::imwrite((dir_ / "rest.png").string(), cv::Mat(24, 32, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_EQ(reference("reference_frames: 0, reference: rest.png"), std::make_pair(cv::Vec3b(1, 2, 3), 3.0));
}

TEST_F(CameraSource, APresetsCameraSectionCropsAndResizesUnlessAParameterSaysOtherwise) {
  write_frame_files(dir_.path(), {frames_[0], frames_[1]});
  write_file(dir_ / "sensor.yaml", "camera:\n  size: [320, 240]\n  fps: 25\n  crop: [40, 0, 240, 240]\n  resize: [120, 120]\n");
  const auto size = [&](const std::string& params) {
    Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 10\n      until: cam.done\n"
                      "      stages:\n        - id: cam\n          plugin: camera_source\n"
                      "          params: {frames: 'frame_{iteration}.png', preset: sensor.yaml" + params + "}\n");
    RunOptions o;
    o.quiet = true;
    o.capture = {"cam.frame", "cam.stamp"};
    const RunResult r = run_pipeline(p, o);
    const auto frame = std::any_cast<MonoColourFramePtr>(r.captured.at("cam.frame"));
    EXPECT_DOUBLE_EQ(std::any_cast<FrameStamp>(r.captured.at("cam.stamp")).timestamp_s, 1 / 25.0);  // the preset's fps
    return frame->image.size();
  };
  EXPECT_EQ(size(""), cv::Size(120, 120));
  EXPECT_EQ(size(", resize: [60, 50]"), cv::Size(60, 50));
  // The crop is of the delivered frame: the preset's, then resized.
  write_file(dir_ / "sensor.yaml", "camera:\n  crop: [300, 0, 40, 40]\n");
  const auto d = errors("stages:\n  - id: cam\n    plugin: camera_source\n"
                        "    params: {frames: 'frame_{iteration}.png', preset: sensor.yaml}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "crop [300, 0, 40, 40] does not fit")) << d[0].str();
}

TEST_F(CameraSource, TimestampsComeFromARecordingsIndex) {
  write_frame_files(dir_.path(), {frames_[0], frames_[1], frames_[2]});
  write_file(dir_ / "index.csv", "index,timestamp_s,file\n0,10.0,frame_0.png\n1,10.5,frame_1.png\n2,10.75,frame_2.png\n");
  Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 10\n      until: cam.done\n"
                    "      stages:\n        - id: cam\n          plugin: camera_source\n"
                    "          params: {frames: index.csv}\n");
  RunOptions o;
  o.quiet = true;
  o.capture = {"cam.stamp"};
  const RunResult r = run_pipeline(p, o);
  EXPECT_DOUBLE_EQ(std::any_cast<FrameStamp>(r.captured.at("cam.stamp")).timestamp_s, 0.75);
  EXPECT_EQ(metric(r, "cam.frames_processed"), 2.0);
}

// Behind a stage slower than the camera, drop_oldest loses frames (each
// counted: every frame captured is processed or counted dropped) and block
// loses none.
TEST_F(CameraSource, FramesLostBehindASlowStageAreCounted) {
  std::vector<cv::Mat> many(40, cv::Mat(24, 32, CV_8UC3, cv::Scalar(50, 50, 50)));
  write_frame_files(dir_.path(), many);
  const auto run = [&](const std::string& policy) {
    Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
                      "      stages:\n        - id: cam\n          plugin: camera_source\n"
                      "          params: {frames: 'frame_{iteration}.png', fps: 500, realtime: true, queue_frames: 1, "
                      "when_behind: " + policy + "}\n"
                      "        - id: slow\n          plugin: test_slow\n          params: {sleep_ms: 10}\n"
                      "          inputs: {input: cam.done}\n");
    RunOptions o;
    o.quiet = true;
    return run_pipeline(p, o);
  };
  const RunResult dropping = run("drop_oldest");
  EXPECT_GT(metric(dropping, "cam.frames_dropped"), 10.0);
  EXPECT_EQ(metric(dropping, "cam.frames_captured"), 39.0);
  EXPECT_EQ(metric(dropping, "cam.frames_processed") + metric(dropping, "cam.frames_dropped"), 39.0);
  const RunResult blocking = run("block");
  EXPECT_EQ(metric(blocking, "cam.frames_dropped"), 0.0);
  EXPECT_EQ(metric(blocking, "cam.frames_processed"), 39.0);
}

// Paced as a camera (a frame every 100 ms), a frame's latency runs from
// when it was due to the chain's end: `done` comes from the frame read
// ahead, so the source does not hold a frame until the next one is due.
TEST_F(CameraSource, ARecordingsDoneCostsNoFramePeriodOfLatency) {
  write_frame_files(dir_.path(), std::vector<cv::Mat>(6, cv::Mat(24, 32, CV_8UC3, cv::Scalar(50, 50, 50))));
  Pipeline p = load("stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
                    "      stages:\n        - id: cam\n          plugin: camera_source\n"
                    "          params: {frames: 'frame_{iteration}.png', fps: 10, realtime: true}\n");
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(metric(r, "cam.frames_processed"), 5.0);
  EXPECT_LT(metric(r, "cam.latency_p50_ms"), 50.0);
}

}  // namespace
