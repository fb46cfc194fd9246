// stereo_image_reader: a user's left and right image files as a stereo frame
// (8-bit grey, or BGR for a colour-pattern sensor), one pair per call; '{iteration}' in a path becomes the loop
// iteration, so a loop can walk through a recorded sequence.
#include <opencv2/imgcodecs.hpp>

#include "touchcloud/io/image_file.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/stereo_frame.hpp"

namespace touchcloud {

namespace {

// A colour-pattern sensor's pattern is its colours: a grey or 16-bit file is
// refused there rather than turned into three equal channels.
cv::Mat read_image(const std::string& file, const char* side, bool colour) {
  const std::string name = std::string("the ") + side + " image " + file;
  return colour ? read_colour_image_file(file, name) : read_image_file(file, cv::IMREAD_GRAYSCALE, name);
}

std::string size_text(const cv::Mat& image) {
  return std::to_string(image.cols) + " x " + std::to_string(image.rows) + " px";
}

}  // namespace

class StereoImageReader final : public Stage {
  std::string left_, right_;
  double fps_ = 30;
  bool colour_ = false;
  long frames_read_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("left", left_, std::string())
        .input_file()
        .doc("left image file (relative to the pipeline file); '{iteration}' becomes the loop iteration (quote such a path in YAML)");
    p.add("right", right_, std::string())
        .input_file()
        .doc("right image file, the same size as the left; '{iteration}' as for left");
    p.add("fps", fps_, 30.0).unit("frames/s").above(0).doc("frame rate: frame k gets timestamp k / fps");
    p.add("colour", colour_, false)
        .doc("read the images as 8-bit BGR (the colour-pattern GelStereo; a grey or 16-bit file is refused); "
             "false: 8-bit grey (the marker sensor)");
  }
  void declare_ports(PortSet& ports) override {
    ports.output<StereoFramePtr>("frame", "the two images, 8-bit grey (or BGR with colour); pose unknown (identity)");
  }

  // Fixed files are read at check time so that `validate` reports them.
  void on_check(RunContext&) override {
    if (left_.find(kIterationField) != std::string::npos || right_.find(kIterationField) != std::string::npos)
      return;
    try {
      read_pair(left_, right_);
    } catch (const InputError& e) {
      throw ParameterError(std::string(e.what()).find("the left image") == 0 ? "left" : "right", e.what());
    }
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    auto frame = std::make_shared<StereoFrame>(read_pair(ctx.with_iteration(left_), ctx.with_iteration(right_)));
    frame->index = frames_read_++;
    frame->timestamp_s = static_cast<double>(frame->index) / fps_;
    io.output<StereoFramePtr>("frame", std::move(frame));
  }

  StereoFrame read_pair(const std::string& left, const std::string& right) const {
    StereoFrame f;
    f.left = read_image(left, "left", colour_);
    f.right = read_image(right, "right", colour_);
    if (f.left.size() != f.right.size())
      throw InputError("the right image " + right + " is " + size_text(f.right) + " but the left image " + left +
                       " is " + size_text(f.left));
    return f;
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StereoImageReader, "stereo_image_reader", source,
                  "Reads a left and a right image file into a stereo frame")
