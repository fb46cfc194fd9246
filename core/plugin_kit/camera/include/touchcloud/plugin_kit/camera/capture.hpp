// One camera as a sequence of frames: a V4L2 device (/dev/videoN or an
// index), a video file, a GStreamer pipeline (where OpenCV was built with
// it), or a recording's image files. Each frame comes
// cropped and resized as asked, with its stamp.
#pragma once

#include <array>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "touchcloud/types/frame_stamp.hpp"

namespace touchcloud::camera {

enum class SourceKind { device, video_file, gstreamer, image_files };

// What a camera's name is: a GStreamer pipeline when it has " ! ", else a
// V4L2 device (/dev/videoN, or N).
SourceKind camera_kind(const std::string& camera);
// "/dev/videoN" for N, else `camera` itself.
std::string device_path(const std::string& camera);
const char* describe(SourceKind kind);

struct CaptureSettings {
  SourceKind kind = SourceKind::video_file;
  std::string source;
  std::optional<std::array<int, 2>> size;  // width, height the camera delivers (requested of a device)
  std::optional<double> fps;               // requested of a device; image files without index.csv: their rate
  std::optional<std::string> pixel_format; // FOURCC requested of a device
  std::optional<std::array<int, 4>> crop;  // x, y, width, height in the delivered image
  std::optional<std::array<int, 2>> resize;
  double open_timeout_s = 5;               // bounded waits for a device or stream to open and deliver
};

struct Shot {
  cv::Mat image;  // BGR, 8-bit, after crop and resize
  FrameStamp stamp;
  // The source's own clock at capture, s: a V4L2 device's buffer time (the
  // monotonic clock every device on the machine shares), a video's frame
  // time, a recording's timestamp_s as written. Two cameras pair on it.
  double clock_s = 0;
  // When the frame was captured, on this machine's steady clock: a device's
  // buffer time, a video paced as a camera its due time (FrameFeed), else
  // when it was read. The chain's latency counts from here.
  std::chrono::steady_clock::time_point captured_at;
  // What follows in a recording, read ahead by its capture thread so that a
  // stage knows it without waiting for the next frame's time: `last` on the
  // final frame, else the next frame's clock_s. Neither for a camera.
  bool last = false;
  std::optional<double> next_clock_s;
};

// A device frame's capture time from its buffer time (`buffer_ms`, V4L2's
// monotonic clock, the steady clock's), read at `now`; `now` itself when
// the buffer time is not on that clock (in the future, or more than a
// second old).
std::chrono::steady_clock::time_point device_capture_time(std::chrono::steady_clock::time_point now,
                                                          double buffer_ms);

// A recording's frame files: a '{iteration}' pattern (0, 1, ... up to the
// first missing file; frame k at k / fps) or an index.csv that lists them
// with their timestamps (column timestamp_s, the file in `file` or `left`).
struct FrameFiles {
  std::vector<std::filesystem::path> files;
  std::vector<double> timestamps_s;  // empty: k / fps
};
FrameFiles list_frame_files(const std::string& source);

// What `validate` can know of a source before the run: a recording is
// opened and its first frame read (returned), so that a file that is not a
// video, a size other than asked or a crop that does not fit is reported; a
// device is checked to exist (nothing returned), a GStreamer pipeline not at
// all. InputError naming the source.
std::optional<cv::Mat> first_frame(const CaptureSettings& settings);

class Capture {
 public:
  // Opens the source; InputError naming it when it cannot be opened, its
  // frame size is not `size`, or a crop does not fit.
  explicit Capture(CaptureSettings settings);
  // The next frame; none at the end of a file or folder. InputError when a
  // frame cannot be read (a file that ends short of its frame count, an
  // unreadable or differently sized image file); RunError when a device
  // stops delivering (unplugged).
  std::optional<Shot> next();
  SourceKind kind() const { return kind_; }
  const CaptureSettings& settings() const { return settings_; }

 private:
  cv::Mat shape(const cv::Mat& raw, const std::string& what) const;
  void check_size(const cv::Mat& raw, const std::string& what) const;

  CaptureSettings settings_;
  SourceKind kind_;
  cv::VideoCapture video_;
  FrameFiles files_;
  std::int64_t frames_expected_ = -1;  // a video file's frame count, when it states one
  std::int64_t read_ = 0;              // frames read so far
  std::int64_t sequence_ = -1;
  std::optional<double> first_ms_;     // a device's first timestamp
  double last_ms_ = 0;
  double frame_ms_ = 0;                // a device's frame period, for gaps
  std::shared_ptr<const std::string> reading_;  // a video file, registered: FFmpeg's log is shared
};

}  // namespace touchcloud::camera
