// image_reader: one camera's image per call, for single-camera sensors (or
// one camera of a stereo sensor): 8-bit grey as a camera image, or 8-bit
// BGR colour as a GelSight-type sensor's frame. `path` names one file, a
// numbered sequence ('{iteration}' becomes the loop iteration) or a glob
// ('frames/*.png', natural order); a sequence is listed before the run, so
// `validate` finds one that matches nothing or lacks a frame, and `last`
// ends a loop cleanly on its last file.
#include <optional>

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/io/image_file.hpp"
#include "touchcloud/io/image_sequence.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/camera_image.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

class ImageReader final : public Stage {
  std::string path_;
  CameraView view_ = CameraView::Mono;
  double fps_ = 30;
  std::string sensor_;
  std::optional<double> mm_per_px_;
  // Listed at check.
  io::SequenceKind kind_ = io::SequenceKind::File;
  std::vector<std::filesystem::path> files_;
  long frames_read_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string())
        .input_file()
        .doc("image file: PNG, JPEG, TIFF, BMP, PNM or WebP (relative to the pipeline file); '{iteration}' becomes the loop iteration, a '*' or '?' in "
             "the file name walks the matching files in natural order (quote such a path in YAML)");
    p.add("view", view_, CameraView::Mono,
          {{"mono", CameraView::Mono}, {"left", CameraView::Left}, {"right", CameraView::Right}})
        .doc("the camera that took it: a single-camera sensor's (mono), or one camera of a stereo sensor");
    p.add("fps", fps_, 30.0).unit("frames/s").above(0).doc("frame rate: frame k gets timestamp k / fps");
    p.add("sensor", sensor_, std::string())
        .doc("colour: the sensor's name (sensor.name), which calibrations are checked against; empty: not checked");
    p.add("mm_per_px", mm_per_px_).unit("mm/px").above(0).doc("colour: the sensor's pixel pitch on the gel");
  }
  void declare_ports(PortSet& ports) override {
    ports.output<CameraImagePtr>("image", "the image, 8-bit grey, with its view; pose unknown (identity)");
    ports.output<MonoColourFramePtr>(
        "colour", "the image, 8-bit BGR (a grey or 16-bit file is refused), as a GelSight-type sensor's frame");
    ports.output<FrameStamp>("stamp", "the file's number in the sequence (from 0), its timestamp and its name");
    ports.output<bool>("last", "true on the sequence's last file (a loop's until), and for a single file");
    ports.metric("frames_read", "frames", "files read so far");
  }

  // Files are listed, and a single one read, at check time so that
  // `validate` reports them.
  void on_check(RunContext&) override {
    try {
      kind_ = io::sequence_kind(path_);
      files_ = io::list_image_sequence(path_);
      if (kind_ == io::SequenceKind::File) read_image_file(path_, cv::IMREAD_GRAYSCALE);
    } catch (const InputError& e) {
      throw ParameterError("path", e.what());
    }
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const std::size_t at = kind_ == io::SequenceKind::Numbered ? static_cast<std::size_t>(std::max(ctx.iteration(), 0))
                           : kind_ == io::SequenceKind::Glob   ? static_cast<std::size_t>(frames_read_)
                                                               : 0;
    if (at >= files_.size())
      throw InputError("image sequence " + path_ + " has " + std::to_string(files_.size()) + " files; file " +
                       std::to_string(at + 1) + " was asked for (end the loop with `until: STAGE.last`)");
    const std::filesystem::path& file = files_[at];
    const long index = frames_read_++;
    const double timestamp_s = static_cast<double>(index) / fps_;
    if (io.wants("image")) {
      auto image = std::make_shared<CameraImage>();
      image->image = read_image_file(file, cv::IMREAD_GRAYSCALE);
      image->view = view_;
      image->index = index;
      image->timestamp_s = timestamp_s;
      io.output<CameraImagePtr>("image", std::move(image));
    }
    if (io.wants("colour")) {
      auto frame = std::make_shared<MonoColourFrame>();
      frame->image = read_colour_image_file(file);
      frame->sensor = sensor_;
      frame->mm_per_px = mm_per_px_.value_or(0);
      frame->index = index;
      frame->timestamp_s = timestamp_s;
      io.output<MonoColourFramePtr>("colour", std::move(frame));
    }
    if (io.wants("stamp")) io.output<FrameStamp>("stamp", FrameStamp{index, timestamp_s, file.filename().string()});
    io.output<bool>("last", at + 1 == files_.size());
    ctx.metric("frames_read", static_cast<double>(frames_read_), "frames");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::ImageReader, "image_reader", source,
                  "Reads one camera's image files, grey or colour, one per call (a single file, a numbered sequence or "
                  "a glob)")
