// stereo_camera_source: a stereo tactile sensor (marker or colour-pattern
// GelStereo) live or recorded, one pair per call: two cameras (V4L2
// devices, GStreamer pipelines, video files or a recording's image files)
// paired by capture time within max_skew_ms, or one camera whose frames
// hold both views side by side. A pair further apart than the skew is
// refused, counted (pairs_refused) and logged; the older frame is let go
// and pairing goes on. The no-contact reference is the mean of the first
// pairs; `done` turns true on a recording's last pair. `crop` and `resize`
// shape each camera's frames (a side-by-side camera's whole frame, before it
// is cut), a sensor file's camera: section gives them as a preset, and
// `record` keeps every frame each camera delivered, lossless, as
// camera_source does (DIR/left and DIR/right, or DIR for one camera).
#include <filesystem>

#include <opencv2/imgproc.hpp>

#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/camera/camera_preset.hpp"
#include "touchcloud/plugin_kit/camera/queue_parameters.hpp"
#include "touchcloud/plugin_kit/camera/recording.hpp"
#include "touchcloud/plugin_kit/camera/stereo_feed.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud {

using camera::SourceKind;

class StereoCameraSource final : public Stage {
  // One camera: each of video, frames, device names it; left_* and right_* two.
  struct Camera {
    std::optional<std::string> video, frames, device;
    int given() const { return video.has_value() + frames.has_value() + device.has_value(); }
    const std::string& source() const { return video ? *video : frames ? *frames : *device; }
    SourceKind kind() const {
      return video ? SourceKind::video_file : frames ? SourceKind::image_files : camera::camera_kind(*device);
    }
    std::string parameter(const std::string& side) const {
      return side + (video ? "video" : frames ? "frames" : "device");
    }
  };
  Camera both_, left_, right_;
  std::optional<std::array<int, 2>> size_, resize_;
  std::optional<std::array<int, 4>> crop_;
  std::optional<double> fps_;
  std::optional<std::string> pixel_format_, preset_, record_;
  double max_skew_ms_ = 10;
  bool colour_ = false;
  int warmup_frames_ = 0, reference_frames_ = 1;
  camera::QueueParameters queue_;

  static void declare_camera(ParameterSet& p, Camera& c, const std::string& side, const std::string& what) {
    p.add(side + "video", c.video).input_file().doc(what + ": a video file (any codec OpenCV's FFmpeg decodes)");
    p.add(side + "frames", c.frames)
        .input_file()
        .doc(what + ": a recording's image files, a '{iteration}' pattern or an index.csv with timestamp_s");
    p.add(side + "device", c.device).doc(what + ": /dev/videoN or N (V4L2), or a GStreamer pipeline (text with ' ! ')");
  }

  void declare_parameters(ParameterSet& p) override {
    declare_camera(p, both_, "", "one camera whose frames hold the left view in their left half, the right in the right");
    declare_camera(p, left_, "left_", "the left camera");
    declare_camera(p, right_, "right_", "the right camera");
    p.add("max_skew_ms", max_skew_ms_, 10.0).at_least(0).unit("ms")
        .doc("two cameras' frames further apart in capture time are refused as a pair (counted in pairs_refused)");
    p.add("size", size_).range(1, 100000).unit("px")
        .doc("width, height each camera delivers (a side-by-side camera: the whole frame): asked of a device, checked "
             "of every frame");
    p.add("fps", fps_).above(0).unit("frames/s")
        .doc("asked of a device; a '{iteration}' recording's frame k is at k / fps (30 when not set)");
    p.add("pixel_format", pixel_format_).doc("FOURCC asked of a device (MJPG, YUYV)");
    p.add("crop", crop_).range(0, 100000).unit("px")
        .doc("x, y, width, height kept of each camera's frame (a side-by-side camera: of the whole frame)");
    p.add("resize", resize_).range(1, 100000).unit("px").doc("width, height after cropping (area interpolation)");
    p.add("preset", preset_)
        .input_file()
        .doc("a sensor file whose camera: section gives size, fps, pixel_format, crop and resize (this stage's own "
             "parameters override it)");
    p.add("record", record_)
        .doc("a folder to record every frame captured into, each camera's in DIR/left and DIR/right (index.csv, "
             "frames/K.png; one side-by-side camera: in DIR), replayed by left_frames: DIR/left/index.csv and "
             "right_frames: DIR/right/index.csv; relative to the current folder, kept whatever ends the run");
    p.add("colour", colour_, false)
        .doc("pairs in 8-bit BGR (the colour-pattern GelStereo); false: 8-bit grey (the marker GelStereo)");
    p.add("warmup_frames", warmup_frames_, 0).range(0, 100000).unit("pairs")
        .doc("pairs read and discarded first (the cameras' exposure settling)");
    p.add("reference_frames", reference_frames_, 1).range(0, 100000).unit("pairs")
        .doc("the no-contact reference is the mean of this many pairs after warm-up, which are not processed (0: no "
             "reference)");
    queue_.declare(p);
    p.rule({"video", "frames", "device", "left_video", "left_frames", "left_device", "right_video", "right_frames",
            "right_device"},
           [this]() -> std::optional<std::string> {
             const int sides = left_.given() + right_.given();
             if (both_.given() == 1 && sides == 0) return std::nullopt;
             if (both_.given() == 0 && left_.given() == 1 && right_.given() == 1) return std::nullopt;
             return "give one side-by-side camera (one of video, frames, device) or two (one of left_video, "
                    "left_frames, left_device and one of right_video, right_frames, right_device)";
           });
    p.rule({"pixel_format"}, [this]() -> std::optional<std::string> {
      if (pixel_format_ && pixel_format_->size() != 4) return "a FOURCC has four characters";
      return std::nullopt;
    });
  }
  void declare_ports(PortSet& ports) override {
    ports.output<StereoFramePtr>("frame", "the pair, 8-bit grey (or BGR with colour), with the left camera's frame "
                                          "number and capture time; pose unknown (identity)");
    ports.output<StereoFramePtr>("reference", "the no-contact reference pair (with reference_frames > 0)");
    ports.output<FrameStamp>("stamp", "the left camera's frame number and capture time");
    ports.output<bool>("done", "true on a recording's last pair (never for a device)");
    ports.metric("pairs_refused", "pairs",
                 "pairs refused so far: two cameras' oldest frames further apart than max_skew_ms, the older let go");
    ports.metric("pair_skew_max_ms", "ms", "the largest capture-time difference within a pair processed")
        .final()
        .lower_is_better();
    camera::FrameTally::declare_metrics(ports, "pair",
                                        "frames the cameras delivered, both counted (a side-by-side frame once), "
                                        "warm-up and reference included");
  }

  std::vector<std::unique_ptr<camera::Recording>> recordings_;  // each camera's, declared before the feed that writes them
  std::unique_ptr<camera::StereoFeed> feed_;
  StereoFramePtr reference_;
  std::optional<camera::ShotPair> pending_;  // a recording's next pair, taken early where only it tells `done`
  camera::FrameTally tally_;
  double skew_max_ms_ = 0;

  bool side_by_side() const { return both_.given() == 1; }
  bool finite() const {
    const auto recorded = [](const Camera& c) { return !c.device.has_value(); };
    return side_by_side() ? recorded(both_) : recorded(left_) && recorded(right_);
  }
  // The preset's values where this stage's parameters are not set.
  camera::CaptureSettings settings(const Camera& c, RunContext* ctx) const {
    camera::CaptureSettings s;
    s.kind = c.kind(), s.source = c.source();
    s.size = size_, s.fps = fps_, s.pixel_format = pixel_format_, s.crop = crop_, s.resize = resize_;
    s.open_timeout_s = queue_.frame_timeout_s;
    if (preset_) camera::fill_from_preset(s, *preset_, ctx);
    return s;
  }
  // The camera's first frame (none for a live camera); ParameterError naming
  // the camera's parameter.
  std::optional<cv::Mat> check_camera(const Camera& c, const std::string& side) const {
    try {
      return camera::first_frame(settings(c, nullptr));
    } catch (const InputError& e) {
      throw ParameterError(c.parameter(side), e.what());
    }
  }
  // Where each camera's recording goes: DIR/left and DIR/right, or DIR.
  std::vector<std::filesystem::path> recording_folders() const {
    const std::filesystem::path dir(*record_);
    if (side_by_side()) return {dir};
    return {dir / "left", dir / "right"};
  }

  // Recordings are opened and their first frames read, so that `validate`
  // reports a side-by-side frame of odd width and two cameras of different sizes.
  void on_check(RunContext&) override {
    if (preset_) {
      try {
        camera::read_camera_preset(*preset_);
      } catch (const InputError& e) {
        throw ParameterError("preset", e.what());
      }
    }
    if (record_)
      for (const auto& folder : recording_folders())
        if (std::filesystem::exists(folder / "index.csv"))
          throw ParameterError("record", "the folder " + folder.string() + " already holds a recording (index.csv)");
    if (side_by_side()) {
      if (const auto frame = check_camera(both_, "")) {
        try {
          camera::StereoFeed::split(*frame, "the first frame of " + both_.source());
        } catch (const InputError& e) {
          throw ParameterError(both_.parameter(""), e.what());
        }
      }
      return;
    }
    const auto left = check_camera(left_, "left_"), right = check_camera(right_, "right_");
    if (left && right && left->size() != right->size())
      throw ParameterError(right_.parameter("right_"),
                           "the right camera's frames are " + std::to_string(right->cols) + " x " +
                               std::to_string(right->rows) + " px but the left camera's are " +
                               std::to_string(left->cols) + " x " + std::to_string(left->rows) + " px");
  }

  // A camera's capture thread and queue, recording into `recording` when given.
  std::unique_ptr<camera::FrameFeed> open(const Camera& c, RunContext& ctx, camera::Recording* recording) const {
    std::function<void(const camera::Shot&)> record;
    if (recording) record = [recording](const camera::Shot& shot) { recording->add(shot); };
    return std::make_unique<camera::FrameFeed>(std::make_unique<camera::Capture>(settings(c, &ctx)),
                                               static_cast<std::size_t>(queue_.queue_frames), queue_.policy(finite()),
                                               queue_.realtime, record);
  }

  void on_configure(RunContext& ctx) override {
    ctx.used("queue_policy", std::string(queue_.policy(finite()) == camera::WhenBehind::block ? "block" : "drop_oldest"));
    if (record_) {
      for (const auto& folder : recording_folders()) recordings_.push_back(std::make_unique<camera::Recording>(folder));
      ctx.log("recording every frame into " + *record_);
    }
    const auto recording = [&](std::size_t k) { return k < recordings_.size() ? recordings_[k].get() : nullptr; };
    feed_ = side_by_side() ? std::make_unique<camera::StereoFeed>(open(both_, ctx, recording(0)))
                           : std::make_unique<camera::StereoFeed>(open(left_, ctx, recording(0)),
                                                                  open(right_, ctx, recording(1)), max_skew_ms_);
    for (int i = 0; i < warmup_frames_; ++i)
      if (!next_pair(ctx)) throw InputError(describe() + " ends within its warm-up pairs");
    if (reference_frames_ > 0) {
      cv::Mat left, right;
      for (int i = 0; i < reference_frames_; ++i) {
        std::optional<camera::ShotPair> pair = next_pair(ctx);
        if (!pair) throw InputError(describe() + " ends within its reference pairs");
        if (left.empty()) left = cv::Mat::zeros(pair->left.image.size(), CV_64FC3), right = left.clone();
        cv::accumulate(pair->left.image, left);
        cv::accumulate(pair->right.image, right);
      }
      camera::ShotPair mean;
      left.convertTo(mean.left.image, CV_8UC3, 1.0 / reference_frames_);
      right.convertTo(mean.right.image, CV_8UC3, 1.0 / reference_frames_);
      reference_ = stereo_frame(mean);
    }
    ctx.log("reading " + describe() + (side_by_side() ? "" : ", pairs within " + format_value(max_skew_ms_) + " ms"));
  }

  std::string describe() const {
    const auto one = [](const Camera& c) { return std::string(camera::describe(c.kind())) + " " + c.source(); };
    return side_by_side() ? "the side-by-side " + one(both_) : "the left " + one(left_) + " and the right " + one(right_);
  }

  // The next pair, the refusals on the way logged.
  std::optional<camera::ShotPair> next_pair(RunContext& ctx) {
    std::optional<camera::ShotPair> pair = feed_->next(queue_.frame_timeout_s);
    for (const camera::RefusedPair& r : feed_->take_refusals())
      ctx.log("pair refused: the left frame at " + format_value(r.left_clock_s) + " s and the right at " +
              format_value(r.right_clock_s) + " s are more than max_skew_ms " + format_value(max_skew_ms_) +
              " ms apart");
    return pair;
  }

  StereoFramePtr stereo_frame(const camera::ShotPair& pair) const {
    auto frame = std::make_shared<StereoFrame>();
    if (colour_) {
      frame->left = pair.left.image, frame->right = pair.right.image;
    } else {
      cv::cvtColor(pair.left.image, frame->left, cv::COLOR_BGR2GRAY);
      cv::cvtColor(pair.right.image, frame->right, cv::COLOR_BGR2GRAY);
    }
    frame->index = static_cast<long>(pair.left.stamp.sequence), frame->timestamp_s = pair.left.stamp.timestamp_s;
    return frame;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    tally_.call_started(camera::Clock::now(), ctx);
    std::optional<camera::ShotPair> pair = pending_ ? std::exchange(pending_, std::nullopt) : next_pair(ctx);
    if (!pair)
      throw InputError(describe() + " has no pair left after " + std::to_string(tally_.processed()) +
                       " processed (end the loop with until: <this stage>.done)");
    tally_.handed_on(pair->left.captured_at);
    skew_max_ms_ = std::max(skew_max_ms_, std::abs(pair->skew_ms));
    io.output("frame", stereo_frame(*pair));
    io.output("stamp", pair->left.stamp);
    if (io.wants("reference")) {
      if (!reference_) throw InputError("the reference is wanted but reference_frames is 0");
      io.output("reference", reference_);
    }
    if (io.wants("done")) {
      std::optional<bool> last = finite() ? feed_->last(*pair) : false;
      if (!last) {  // the frames after this pair too far apart to tell: the next pair decides
        pending_ = next_pair(ctx);
        last = !pending_;
      }
      io.output("done", *last);
    }
    ctx.metric("frames_dropped", static_cast<double>(feed_->dropped()), "frames");
    ctx.metric("pairs_refused", static_cast<double>(feed_->refused()), "pairs");
  }

  void on_finish(RunContext& ctx) override {
    tally_.finish(ctx, feed_->captured());
    ctx.metric("pair_skew_max_ms", skew_max_ms_, "ms");
    if (feed_->refused() > 0)
      ctx.log(std::to_string(feed_->refused()) + " pairs refused: frames more than max_skew_ms " +
              format_value(max_skew_ms_) + " ms apart");
    feed_.reset();
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StereoCameraSource, "stereo_camera_source", source,
                  "A stereo sensor's pairs, live or recorded: two cameras paired by capture time within a skew, or "
                  "one side-by-side camera")
