// image_reader: one camera's image file as a camera image (8-bit grey), one
// per call, for single-camera sensors (or one camera of a stereo sensor);
// '{iteration}' in the path becomes the loop iteration, so a loop can walk
// through a recorded sequence.
#include <opencv2/imgcodecs.hpp>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/camera_image.hpp"

namespace touchcloud {

class ImageReader final : public Stage {
  std::string path_;
  CameraView view_ = CameraView::Mono;
  double fps_ = 30;
  long frames_read_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("path", path_, std::string())
        .input_file()
        .doc("image file (relative to the pipeline file); '{iteration}' becomes the loop iteration (quote such a "
             "path in YAML)");
    p.add("view", view_, CameraView::Mono,
          {{"mono", CameraView::Mono}, {"left", CameraView::Left}, {"right", CameraView::Right}})
        .doc("the camera that took it: a single-camera sensor's (mono), or one camera of a stereo sensor");
    p.add("fps", fps_, 30.0).unit("frames/s").above(0).doc("frame rate: frame k gets timestamp k / fps");
  }
  void declare_ports(PortSet& ports) override {
    ports.output<CameraImagePtr>("image", "the image, 8-bit grey, with its view; pose unknown (identity)");
  }

  // A fixed file is read at check time so that `validate` reports it.
  void on_check(RunContext&) override {
    if (path_.find(kIterationField) != std::string::npos) return;
    try {
      read(path_);
    } catch (const InputError& e) {
      throw ParameterError("path", e.what());
    }
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    auto image = std::make_shared<CameraImage>();
    image->image = read(ctx.with_iteration(path_));
    image->view = view_;
    image->index = frames_read_++;
    image->timestamp_s = static_cast<double>(image->index) / fps_;
    io.output<CameraImagePtr>("image", std::move(image));
  }

  static cv::Mat read(const std::string& file) {
    cv::Mat image = cv::imread(file, cv::IMREAD_GRAYSCALE);
    if (image.empty())
      throw InputError("the image " + file + " cannot be read (missing, unreadable or not an image format OpenCV knows)");
    return image;
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::ImageReader, "image_reader", source,
                  "Reads one camera's image file (a single-camera sensor, or one camera of a stereo pair)")
