#include "touchcloud/plugin_kit/camera/capture.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/io/image_file.hpp"
#include "ffmpeg_messages.hpp"

namespace fs = std::filesystem;

namespace touchcloud::camera {

namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// A recording's index.csv: a header naming `timestamp_s` and the frame's
// file column (`file`, or a stereo dataset's `left`), paths relative to it.
FrameFiles read_index(const fs::path& index) {
  std::ifstream in(index);
  std::string line;
  if (!std::getline(in, line)) throw InputError(index.string() + " cannot be read: no header line");
  const auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::stringstream ss(text);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (!text.empty() && text.back() == ',') cells.emplace_back();
    return cells;
  };
  const std::vector<std::string> header = split(line);
  const auto col = [&](std::initializer_list<const char*> names) -> std::size_t {
    for (const char* name : names)
      if (auto it = std::find(header.begin(), header.end(), name); it != header.end())
        return static_cast<std::size_t>(it - header.begin());
    throw InputError(index.string() + " has no column '" + *names.begin() + "'");
  };
  const std::size_t file_col = col({"file", "left"}), time_col = col({"timestamp_s"});
  FrameFiles out;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    const std::string where = index.string() + ":" + std::to_string(row) + ": ";
    if (cells.size() != header.size())
      throw InputError(where + std::to_string(cells.size()) + " cells, the header has " + std::to_string(header.size()));
    try {
      out.timestamps_s.push_back(std::stod(cells[time_col]));
    } catch (const std::exception&) {
      throw InputError(where + "timestamp_s '" + cells[time_col] + "' is not a number");
    }
    out.files.push_back(index.parent_path() / cells[file_col]);
  }
  if (out.files.empty()) throw InputError(index.string() + " lists no frames");
  return out;
}

}  // namespace

SourceKind camera_kind(const std::string& camera) {
  return camera.find(" ! ") != std::string::npos ? SourceKind::gstreamer : SourceKind::device;
}

std::string device_path(const std::string& camera) { return all_digits(camera) ? "/dev/video" + camera : camera; }

const char* describe(SourceKind kind) {
  switch (kind) {
    case SourceKind::device: return "camera";
    case SourceKind::video_file: return "video file";
    case SourceKind::gstreamer: return "GStreamer pipeline";
    case SourceKind::image_files: return "image files";
  }
  return "?";
}

FrameFiles list_frame_files(const std::string& source) {
  if (fs::path(source).extension() == ".csv") return read_index(source);
  FrameFiles out;
  const std::size_t at = source.find("{iteration}");
  if (at == std::string::npos)
    throw InputError(source + " is neither a recording's index.csv nor a '{iteration}' pattern of its frame files");
  for (long k = 0;; ++k) {
    const fs::path file = source.substr(0, at) + std::to_string(k) + source.substr(at + 11);
    if (!fs::exists(file)) break;
    out.files.push_back(file);
  }
  if (out.files.empty())
    throw InputError("no frame file " + source + " (the first, with {iteration} 0, does not exist)");
  return out;
}

std::chrono::steady_clock::time_point device_capture_time(std::chrono::steady_clock::time_point now,
                                                          double buffer_ms) {
  const std::chrono::steady_clock::time_point buffer{std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double, std::milli>(buffer_ms))};
  return buffer <= now && now - buffer < std::chrono::seconds(1) ? buffer : now;
}

std::optional<cv::Mat> first_frame(const CaptureSettings& s) {
  if (s.kind == SourceKind::gstreamer) return std::nullopt;
  if (s.kind == SourceKind::device) {
    const std::string path = device_path(s.source);
    if (!fs::exists(path)) throw InputError("the camera " + path + " does not exist (no such device)");
    return std::nullopt;
  }
  if (s.pixel_format) throw InputError("pixel_format is asked of a device, not of " + s.source);
  Capture capture(s);
  std::optional<Shot> shot = capture.next();
  if (!shot) throw InputError(s.source + " holds no frame");
  return shot->image;
}

Capture::Capture(CaptureSettings settings) : settings_(std::move(settings)), kind_(settings_.kind) {
  const std::string& source = settings_.source;
  const std::vector<int> timeouts = {cv::CAP_PROP_OPEN_TIMEOUT_MSEC, static_cast<int>(settings_.open_timeout_s * 1000),
                                     cv::CAP_PROP_READ_TIMEOUT_MSEC, static_cast<int>(settings_.open_timeout_s * 1000)};
  switch (kind_) {
    case SourceKind::image_files:
      files_ = list_frame_files(source);
      return;
    case SourceKind::video_file: {
      if (!fs::is_regular_file(source)) throw InputError("the video file " + source + " does not exist");
      catch_ffmpeg_messages();
      caught_ffmpeg_messages();
      reading_ = reading_video(source);
      const bool opened = video_.open(source, cv::CAP_FFMPEG, timeouts) && video_.isOpened();
      const std::vector<std::string> said = caught_ffmpeg_messages();
      if (!opened)
        throw InputError("the video file " + source + " cannot be opened: not a video OpenCV's FFmpeg can decode" +
                         (said.empty() ? "" : " (" + ffmpeg_says(said, reading_) + ")"));
      if (!said.empty())
        throw InputError("the video file " + source + " is damaged: " + ffmpeg_says(said, reading_));
      if (const double n = video_.get(cv::CAP_PROP_FRAME_COUNT); n > 0) frames_expected_ = static_cast<std::int64_t>(n);
      break;
    }
    case SourceKind::gstreamer:
      if (!video_.open(source, cv::CAP_GSTREAMER) || !video_.isOpened())
        throw InputError("the GStreamer pipeline '" + source + "' cannot be opened (is OpenCV built with GStreamer?)");
      break;
    case SourceKind::device: {
      const std::string device = device_path(source);
      if (!fs::exists(device)) throw InputError("the camera " + device + " does not exist (no such device)");
      std::vector<int> params = timeouts;
      if (settings_.pixel_format) {
        const std::string& f = *settings_.pixel_format;
        params.insert(params.end(), {cv::CAP_PROP_FOURCC, cv::VideoWriter::fourcc(f[0], f[1], f[2], f[3])});
      }
      if (settings_.size)
        params.insert(params.end(), {cv::CAP_PROP_FRAME_WIDTH, (*settings_.size)[0], cv::CAP_PROP_FRAME_HEIGHT,
                                     (*settings_.size)[1]});
      if (!video_.open(device, cv::CAP_V4L2, params) || !video_.isOpened())
        throw InputError("the camera " + device + " cannot be opened (busy, not a capture device, or no permission)");
      if (settings_.fps) video_.set(cv::CAP_PROP_FPS, *settings_.fps);
      const double fps = video_.get(cv::CAP_PROP_FPS);
      frame_ms_ = fps > 0 ? 1000.0 / fps : 0;
      break;
    }
  }
}

void Capture::check_size(const cv::Mat& raw, const std::string& what) const {
  if (settings_.size && (raw.cols != (*settings_.size)[0] || raw.rows != (*settings_.size)[1]))
    throw InputError(what + " is " + std::to_string(raw.cols) + " x " + std::to_string(raw.rows) + " px, not the " +
                     std::to_string((*settings_.size)[0]) + " x " + std::to_string((*settings_.size)[1]) +
                     " px of 'size'");
  if (settings_.crop) {
    const auto& c = *settings_.crop;
    if (c[0] < 0 || c[1] < 0 || c[2] <= 0 || c[3] <= 0 || c[0] + c[2] > raw.cols || c[1] + c[3] > raw.rows)
      throw InputError("crop [" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
                       ", " + std::to_string(c[3]) + "] does not fit " + what + "'s " + std::to_string(raw.cols) +
                       " x " + std::to_string(raw.rows) + " px");
  }
}

cv::Mat Capture::shape(const cv::Mat& raw, const std::string& what) const {
  check_size(raw, what);
  cv::Mat bgr;
  if (raw.channels() == 1) cv::cvtColor(raw, bgr, cv::COLOR_GRAY2BGR);
  else if (raw.channels() == 4) cv::cvtColor(raw, bgr, cv::COLOR_BGRA2BGR);
  else bgr = raw;
  if (settings_.crop) {
    const auto& c = *settings_.crop;
    bgr = bgr(cv::Rect(c[0], c[1], c[2], c[3]));
  }
  if (settings_.resize) {
    cv::Mat out;
    cv::resize(bgr, out, cv::Size((*settings_.resize)[0], (*settings_.resize)[1]), 0, 0, cv::INTER_AREA);
    return out;
  }
  return bgr.isContinuous() && bgr.data != raw.data ? bgr : bgr.clone();
}

std::optional<Shot> Capture::next() {
  Shot shot;
  if (kind_ == SourceKind::image_files) {
    if (read_ >= static_cast<std::int64_t>(files_.files.size())) return std::nullopt;
    const fs::path& file = files_.files[static_cast<std::size_t>(read_)];
    shot.image = shape(read_image_file(file, cv::IMREAD_UNCHANGED), "the image " + file.string());
    shot.captured_at = std::chrono::steady_clock::now();
    const double fps = settings_.fps.value_or(30.0);
    shot.clock_s = files_.timestamps_s.empty() ? static_cast<double>(read_) / fps
                                               : files_.timestamps_s[static_cast<std::size_t>(read_)];
    shot.stamp.timestamp_s = shot.clock_s - (files_.timestamps_s.empty() ? 0.0 : files_.timestamps_s.front());
    shot.stamp.sequence = read_++;
    return shot;
  }
  cv::Mat raw;
  const bool delivered = video_.read(raw) && !raw.empty();
  // The decoder hides damage in the frame it returns, and says so only in
  // its log: a damaged frame is an error, not a picture of concealment.
  if (const std::vector<std::string> said = kind_ == SourceKind::video_file ? caught_ffmpeg_messages()
                                                                           : std::vector<std::string>();
      !said.empty())
    throw InputError("the video file " + settings_.source + " is damaged at or before its frame " +
                     std::to_string(read_) +
                     (frames_expected_ > 0 ? " of " + std::to_string(frames_expected_) : std::string()) +
                     " (corrupt or cut short): " + ffmpeg_says(said, reading_));
  if (!delivered) {
    if (kind_ == SourceKind::video_file && frames_expected_ > 0 && read_ < frames_expected_)
      throw InputError("the video file " + settings_.source + " ends after " + std::to_string(read_) + " of its " +
                       std::to_string(frames_expected_) + " frames: it is cut short or damaged");
    if (kind_ == SourceKind::video_file) {
      reading_.reset();
      return std::nullopt;
    }
    throw RunError("the " + std::string(describe(kind_)) + " " + settings_.source + " stopped delivering frames after " +
                   std::to_string(read_) + " (unplugged, or no frame within " +
                   std::to_string(static_cast<int>(settings_.open_timeout_s)) + " s)");
  }
  const auto read_at = std::chrono::steady_clock::now();
  shot.image = shape(raw, "the " + std::string(describe(kind_)) + " " + settings_.source + "'s frame " +
                              std::to_string(read_));
  const double ms = video_.get(cv::CAP_PROP_POS_MSEC);
  shot.captured_at = kind_ == SourceKind::device ? device_capture_time(read_at, ms) : read_at;
  if (!first_ms_) first_ms_ = ms;
  // A device numbers its frames by its clock: a step of more than one
  // frame period is frames it dropped before we saw them.
  std::int64_t step = 1;
  if (kind_ != SourceKind::video_file && sequence_ >= 0 && frame_ms_ > 0 && ms > last_ms_)
    step = std::max<std::int64_t>(1, std::llround((ms - last_ms_) / frame_ms_));
  sequence_ = kind_ == SourceKind::video_file ? read_ : sequence_ + step;
  last_ms_ = ms;
  shot.stamp.sequence = sequence_;
  shot.stamp.timestamp_s = (ms - *first_ms_) / 1000.0;
  shot.clock_s = ms / 1000.0;
  ++read_;
  return shot;
}

}  // namespace touchcloud::camera
