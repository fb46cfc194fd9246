// camera_source: a single-camera tactile sensor (GelSight-type, DIGIT) live
// or recorded, one frame per call: a V4L2 device or GStreamer pipeline, a
// video file, or a recording's image files. Capture runs on its own thread
// into a bounded queue; the no-contact reference is the mean of the first
// frames (or an image file), and `done` turns true on a recording's last
// frame, so a loop `until: cam.done` walks a whole file.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/plugin_kit/camera/camera_preset.hpp"
#include "touchcloud/plugin_kit/camera/frame_feed.hpp"
#include "touchcloud/plugin_kit/camera/frame_tally.hpp"
#include "touchcloud/plugin_kit/camera/queue_parameters.hpp"
#include "touchcloud/plugin_kit/camera/recording.hpp"
#include "touchcloud/io/image_file.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

using camera::SourceKind;
using camera::WhenBehind;

class CameraSource final : public Stage {
  std::optional<std::string> video_, frames_, device_, preset_, reference_file_, record_;
  std::string sensor_;
  std::optional<std::array<int, 2>> size_, resize_;
  std::optional<std::array<int, 4>> crop_;
  std::optional<double> fps_;
  std::optional<std::string> pixel_format_;
  int warmup_frames_ = 0, reference_frames_ = 1;
  camera::QueueParameters queue_;

  void declare_parameters(ParameterSet& p) override {
    p.add("video", video_).input_file().doc("a video file (any codec OpenCV's FFmpeg decodes)");
    p.add("frames", frames_)
        .input_file()
        .doc("a recording's image files: a '{iteration}' pattern (0, 1, ... up to the first missing file) or an "
             "index.csv listing them with timestamp_s (file column 'file', or a stereo dataset's 'left')");
    p.add("device", device_)
        .doc("a camera: /dev/videoN or its number N (V4L2), or a GStreamer pipeline (text with ' ! ')");
    p.add("preset", preset_)
        .input_file()
        .doc("a sensor file whose camera: section gives size, fps, pixel_format, crop and resize (this stage's own "
             "parameters override it)");
    p.add("size", size_).range(1, 100000).unit("px")
        .doc("width, height the camera delivers: asked of a device, checked of every frame");
    p.add("fps", fps_).above(0).unit("frames/s")
        .doc("asked of a device; a '{iteration}' recording's frame k is at k / fps (30 when not set)");
    p.add("pixel_format", pixel_format_).doc("FOURCC asked of a device (MJPG, YUYV)");
    p.add("crop", crop_).range(0, 100000).unit("px").doc("x, y, width, height kept of each delivered frame");
    p.add("resize", resize_).range(1, 100000).unit("px").doc("width, height after cropping (area interpolation)");
    p.add("warmup_frames", warmup_frames_, 0).range(0, 100000).unit("frames")
        .doc("frames read and discarded first (a camera's exposure settling)");
    p.add("reference_frames", reference_frames_, 1).range(0, 100000).unit("frames")
        .doc("the no-contact reference is the mean of this many frames after warm-up, which are not processed (0: "
             "'reference' names a file)");
    p.add("reference", reference_file_).input_file()
        .doc("the no-contact reference as an image file instead (with reference_frames: 0)");
    queue_.declare(p);
    p.add("record", record_)
        .doc("a folder to record every frame captured into (index.csv, frames/K.png; relative to the current "
             "directory), written as frames arrive and kept whatever ends the run; frames: FOLDER/index.csv replays it");
    p.add("sensor", sensor_, std::string()).doc("the sensor's name on its frames (calibrations belong to one sensor)");
    p.rule({"video", "frames", "device"}, [this]() -> std::optional<std::string> {
      const int given = video_.has_value() + frames_.has_value() + device_.has_value();
      if (given != 1) return "give exactly one of video, frames and device";
      return std::nullopt;
    });
    p.rule({"reference_frames", "reference"}, [this]() -> std::optional<std::string> {
      if ((reference_frames_ == 0) != reference_file_.has_value())
        return "the reference is either the mean of reference_frames (> 0) or the file 'reference' (with "
               "reference_frames: 0)";
      return std::nullopt;
    });
    p.rule({"pixel_format"}, [this]() -> std::optional<std::string> {
      if (pixel_format_ && pixel_format_->size() != 4) return "a FOURCC has four characters";
      return std::nullopt;
    });
  }
  void declare_ports(PortSet& ports) override {
    ports.output<MonoColourFramePtr>("frame", "the frame, 8-bit BGR, with its stamp (index, timestamp_s)");
    ports.output<CameraImagePtr>("image", "the frame, 8-bit grey, view mono, with its stamp");
    ports.output<MonoColourFramePtr>("reference", "the no-contact reference, 8-bit BGR");
    ports.output<CameraImagePtr>("reference_image", "the no-contact reference, 8-bit grey");
    ports.output<FrameStamp>("stamp", "the frame's sequence number and capture time");
    ports.output<bool>("done", "true on a recording's last frame (never for a device)");
    camera::FrameTally::declare_metrics(ports, "frame", "frames delivered by the camera after warm-up and reference");
  }

  camera::CaptureSettings settings_;
  std::unique_ptr<camera::Recording> recording_;
  std::unique_ptr<camera::FrameFeed> feed_;
  MonoColourFramePtr reference_;
  CameraImagePtr reference_grey_;
  camera::FrameTally tally_;
  camera::SequenceGaps gaps_;

  std::string source() const { return video_ ? *video_ : frames_ ? *frames_ : device_.value_or(""); }
  SourceKind kind() const {
    return video_ ? SourceKind::video_file : frames_ ? SourceKind::image_files : camera::camera_kind(*device_);
  }
  bool finite() const { return kind() == SourceKind::image_files || kind() == SourceKind::video_file; }
  const char* source_parameter() const { return video_ ? "video" : frames_ ? "frames" : "device"; }

  // The preset's values where this stage's parameters are not set.
  camera::CaptureSettings capture_settings(RunContext* ctx) const {
    camera::CaptureSettings s;
    s.kind = kind();
    s.source = source();
    s.size = size_, s.fps = fps_, s.pixel_format = pixel_format_, s.crop = crop_, s.resize = resize_;
    s.open_timeout_s = queue_.frame_timeout_s;
    if (preset_) camera::fill_from_preset(s, *preset_, ctx);
    return s;
  }

  // A recording is opened and its first frame read, so that `validate`
  // reports a file that is not a video, a size other than asked, a crop
  // that does not fit; a device, that it exists.
  void on_check(RunContext&) override {
    camera::CaptureSettings s;
    try {
      s = capture_settings(nullptr);
    } catch (const InputError& e) {
      throw ParameterError("preset", e.what());
    }
    try {
      if (!camera::first_frame(s)) return;
    } catch (const InputError& e) {
      throw ParameterError(source_parameter(), e.what());
    }
    if (record_ && std::filesystem::exists(std::filesystem::path(*record_) / "index.csv"))
      throw ParameterError("record", "the folder " + *record_ + " already holds a recording (index.csv)");
    if (reference_file_) {
      try {
        read_image_file(*reference_file_, cv::IMREAD_COLOR);
      } catch (const InputError& e) {
        throw ParameterError("reference", e.what());
      }
    }
  }

  void on_configure(RunContext& ctx) override {
    settings_ = capture_settings(&ctx);
    const WhenBehind policy = queue_.policy(finite());
    ctx.used("queue_policy", std::string(policy == WhenBehind::block ? "block" : "drop_oldest"));
    std::function<void(const camera::Shot&)> record;
    if (record_) {
      recording_ = std::make_unique<camera::Recording>(*record_);
      record = [this](const camera::Shot& shot) { recording_->add(shot); };
      ctx.log("recording every frame into " + *record_);
    }
    feed_ = std::make_unique<camera::FrameFeed>(std::make_unique<camera::Capture>(settings_),
                                                static_cast<std::size_t>(queue_.queue_frames), policy, queue_.realtime,
                                                record);
    for (int i = 0; i < warmup_frames_; ++i) {
      std::optional<camera::Shot> shot = feed_->next(queue_.frame_timeout_s);
      if (!shot) throw InputError(source() + " ends within its warm-up frames");
      gaps_.see(shot->stamp.sequence, feed_->first_sequence());
    }
    cv::Mat reference;
    if (reference_frames_ > 0) {
      cv::Mat sum;
      for (int i = 0; i < reference_frames_; ++i) {
        std::optional<camera::Shot> shot = feed_->next(queue_.frame_timeout_s);
        if (!shot) throw InputError(source() + " ends within its reference frames");
        gaps_.see(shot->stamp.sequence, feed_->first_sequence());
        if (sum.empty()) sum = cv::Mat::zeros(shot->image.size(), CV_64FC3);
        cv::accumulate(shot->image, sum);
      }
      sum.convertTo(reference, CV_8UC3, 1.0 / reference_frames_);
    } else {
      reference = read_image_file(*reference_file_, cv::IMREAD_COLOR);
    }
    auto frame = std::make_shared<MonoColourFrame>();
    frame->image = reference, frame->sensor = sensor_;
    reference_ = frame;
    reference_grey_ = grey(reference, {});
    ctx.log(std::string("reading the ") + camera::describe(kind()) + " " + source());
  }

  static CameraImagePtr grey(const cv::Mat& bgr, const FrameStamp& stamp) {
    auto image = std::make_shared<CameraImage>();
    cv::cvtColor(bgr, image->image, cv::COLOR_BGR2GRAY);
    image->index = static_cast<long>(stamp.sequence), image->timestamp_s = stamp.timestamp_s;
    return image;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    tally_.call_started(camera::Clock::now(), ctx);
    std::optional<camera::Shot> shot = feed_->next(queue_.frame_timeout_s);
    if (!shot)
      throw InputError(source() + " has no frame left after " + std::to_string(tally_.processed()) +
                       " processed (end the loop with until: <this stage>.done)");
    gaps_.see(shot->stamp.sequence, feed_->first_sequence());
    tally_.handed_on(shot->captured_at);
    ctx.metric("frames_dropped", static_cast<double>(gaps_.dropped()), "frames");

    auto frame = std::make_shared<MonoColourFrame>();
    frame->image = shot->image, frame->sensor = sensor_;
    frame->index = static_cast<long>(shot->stamp.sequence), frame->timestamp_s = shot->stamp.timestamp_s;
    if (io.wants("image")) io.output("image", grey(shot->image, shot->stamp));
    io.output("frame", MonoColourFramePtr(frame));
    io.output("reference", reference_);
    io.output("reference_image", reference_grey_);
    io.output("stamp", shot->stamp);
    if (io.wants("done")) io.output("done", finite() && shot->last);
  }

  void on_finish(RunContext& ctx) override {
    tally_.finish(ctx, feed_->captured() - warmup_frames_ - reference_frames_);
    feed_.reset();
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::CameraSource, "camera_source", source,
                  "A single-camera sensor's frames, live or recorded: a V4L2 device, a video file or image files, "
                  "captured on their own thread")
