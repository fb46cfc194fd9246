// stereo_camera_source pairs two cameras' frames by capture time: a pair
// further apart than max_skew_ms is refused and counted (frames dropped from
// one camera, one camera's clock shifted, two frame rates), never a hang;
// and refuses at validation what cannot make pairs: a side-by-side frame of
// odd width, two cameras of different sizes, a camera that does not exist,
// sources given other than as one side-by-side camera or two.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline_fixture.hpp"
#include "stereo_presses.hpp"
#include "touchcloud/types/frame_stamp.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

class StereoPairing : public PipelineFixture {
 protected:
  void SetUp() override { pairs_ = stereo_presses(); }
  static std::string source_stage(const std::string& params) {
    return "stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
           "      stages:\n        - id: cam\n          plugin: stereo_camera_source\n          params: {" + params + "}\n";
  }
  RunResult run(const std::string& params) {
    Pipeline p = load(source_stage(params));
    RunOptions o;
    o.capture = {"cam.stamp"};
    o.log_sink = [this](const std::string& line) { log_ += line; };
    return run_pipeline(p, o);
  }
  std::string load_error(const std::string& params) {
    const auto d = errors(source_stage(params));
    if (d.size() != 1) return "expected one diagnostic, got " + std::to_string(d.size());
    return d[0].message;
  }
  static double metric(const RunResult& r, const std::string& key) { return r.record.metrics.at(key).values.back(); }

  std::vector<ViewPair> pairs_;
  std::string log_;
};

const std::vector<double> kTimes = {0.0, 0.033, 0.067, 0.1};

TEST_F(StereoPairing, AFrameDroppedFromOneCameraCostsOneRefusedPair) {
  write_side(dir_.path(), "left", lefts(pairs_), kTimes);
  write_side(dir_.path(), "right", {pairs_[0].right, pairs_[1].right, pairs_[3].right}, {0.0, 0.033, 0.1});
  const RunResult r = run("left_frames: left.csv, right_frames: right.csv");
  EXPECT_EQ(metric(r, "cam.pairs_refused"), 1.0);
  EXPECT_EQ(metric(r, "cam.frames_processed"), 2.0);  // (1, 1) and (3, 3); left 2 has no partner
  EXPECT_EQ(std::any_cast<FrameStamp>(r.captured.at("cam.stamp")).sequence, 3);
  EXPECT_NE(log_.find("pair refused: the left frame at 0.067 s and the right at 0.1 s"), std::string::npos) << log_;
  EXPECT_NE(log_.find("1 pairs refused"), std::string::npos) << log_;
}

TEST_F(StereoPairing, AFrameOfOneCameraLateByMoreThanTheSkewIsRefused) {
  write_side(dir_.path(), "left", lefts(pairs_), kTimes);
  write_side(dir_.path(), "right", rights(pairs_), {0.0, 0.033, 0.087, 0.1});  // frame 2 20 ms late
  const RunResult late = run("left_frames: left.csv, right_frames: right.csv");
  // Left 2 is refused against right 2, then right 2 against left 3.
  EXPECT_EQ(metric(late, "cam.pairs_refused"), 2.0);
  EXPECT_EQ(metric(late, "cam.frames_processed"), 2.0);
  // A skew that allows it pairs every frame.
  const RunResult allowed = run("left_frames: left.csv, right_frames: right.csv, max_skew_ms: 25");
  EXPECT_EQ(metric(allowed, "cam.pairs_refused"), 0.0);
  EXPECT_EQ(metric(allowed, "cam.frames_processed"), 3.0);
  EXPECT_NEAR(metric(allowed, "cam.pair_skew_max_ms"), 20.0, 1e-9);
}

TEST_F(StereoPairing, TwoVideosAtDifferentRatesPairOnlyFramesWithinTheSkew) {
  std::vector<cv::Mat> left, right;
  for (int k = 0; k < 9; ++k) left.push_back(pairs_[k % 4].left), right.push_back(pairs_[k % 4].right);
  write_video(dir_ / "left.mkv", left, 25);   // a frame every 40 ms
  write_video(dir_ / "right.mkv", right, 20); // every 50 ms
  const RunResult r = run("left_video: left.mkv, right_video: right.mkv, max_skew_ms: 12");
  // After the reference (0, 0): (40, 50), (160, 150), (200, 200), (240, 250)
  // paired; 80, 100, 120, 280, 300, 320 refused.
  EXPECT_EQ(metric(r, "cam.frames_processed"), 4.0);
  EXPECT_EQ(metric(r, "cam.pairs_refused"), 6.0);
  EXPECT_NEAR(metric(r, "cam.pair_skew_max_ms"), 10.0, 1e-6);
}

TEST_F(StereoPairing, OneCameraEndingEndsThePairs) {
  write_side(dir_.path(), "left", lefts(pairs_), kTimes);
  write_side(dir_.path(), "right", {pairs_[0].right, pairs_[1].right}, {0.0, 0.033});
  const RunResult r = run("left_frames: left.csv, right_frames: right.csv");
  EXPECT_EQ(metric(r, "cam.frames_processed"), 1.0);
  EXPECT_EQ(metric(r, "cam.pairs_refused"), 0.0);
}

// Paced as cameras (a pair every 100 ms), `done` comes from the frames read
// ahead: no pair is held until the next one is due, so its latency is under
// a frame period.
TEST_F(StereoPairing, ARecordingsDoneCostsNoFramePeriodOfLatency) {
  for (const std::string side : {"left", "right"})
    for (int k = 0; k < 6; ++k)
      cv::imwrite((dir_ / (side + "_" + std::to_string(k) + ".png")).string(),
                  side == "left" ? pairs_[k % 4].left : pairs_[k % 4].right);
  const RunResult r = run("left_frames: 'left_{iteration}.png', right_frames: 'right_{iteration}.png', fps: 10, "
                          "realtime: true");
  EXPECT_EQ(metric(r, "cam.frames_processed"), 5.0);
  EXPECT_LT(metric(r, "cam.latency_p50_ms"), 50.0);
}

TEST_F(StereoPairing, ASideBySideFrameOfOddWidthIsRefusedAtValidation) {
  cv::Mat odd(360, 641, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::imwrite((dir_ / "both_0.png").string(), odd);
  const std::string e = load_error("frames: 'both_{iteration}.png'");
  EXPECT_NE(e.find("parameter 'frames'"), std::string::npos) << e;
  EXPECT_NE(e.find("is 641 x 360 px: a side-by-side frame needs an even width"), std::string::npos) << e;
}

TEST_F(StereoPairing, TwoCamerasOfDifferentSizesAreRefusedAtValidation) {
  write_side(dir_.path(), "left", lefts(pairs_), kTimes);
  cv::Mat small;
  cv::resize(pairs_[0].right, small, cv::Size(320, 180));
  write_side(dir_.path(), "right", {small}, {0.0});
  const std::string e = load_error("left_frames: left.csv, right_frames: right.csv");
  EXPECT_NE(e.find("parameter 'right_frames'"), std::string::npos) << e;
  EXPECT_NE(e.find("the right camera's frames are 320 x 180 px but the left camera's are 640 x 360 px"),
            std::string::npos)
      << e;
}

TEST_F(StereoPairing, ACameraThatDoesNotExistIsRefusedNamingItsSide) {
  write_side(dir_.path(), "left", lefts(pairs_), kTimes);
  const std::string e = load_error("left_frames: left.csv, right_device: /dev/video97");
  EXPECT_NE(e.find("parameter 'right_device': the camera /dev/video97 does not exist"), std::string::npos) << e;
}

TEST_F(StereoPairing, OneSideBySideCameraOrTwoCameras) {
  write_side(dir_.path(), "left", lefts(pairs_), kTimes);
  const std::string rule = "give one side-by-side camera (one of video, frames, device) or two";
  EXPECT_NE(load_error("left_frames: left.csv").find(rule), std::string::npos);
  EXPECT_NE(load_error("frames: left.csv, left_frames: left.csv, right_frames: left.csv").find(rule), std::string::npos);
  EXPECT_NE(load_error("left_frames: left.csv, right_frames: left.csv, right_video: left.csv").find(rule),
            std::string::npos);
}

TEST_F(StereoPairing, AReferenceWantedWithoutReferenceFramesIsAnError) {
  write_side(dir_.path(), "left", lefts(pairs_), kTimes);
  write_side(dir_.path(), "right", rights(pairs_), kTimes);
  Pipeline p = load(source_stage("left_frames: left.csv, right_frames: right.csv, reference_frames: 0") +
                    "        - id: rectify_reference\n          plugin: stereo_rectification\n"
                    "          params: {sensor: " + (source_dir() / "sample_clouds/colour_recording/sensor.yaml").string() +
                    "}\n          inputs: {frame: cam.reference}\n");
  RunOptions o;
  o.quiet = true;
  try {
    run_pipeline(p, o);
    ADD_FAILURE() << "ran without a reference";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the reference is wanted but reference_frames is 0"), std::string::npos)
        << e.what();
  }
}

}  // namespace
