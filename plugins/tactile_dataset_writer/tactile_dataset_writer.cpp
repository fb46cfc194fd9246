// tactile_dataset_writer: tactile images of a GelSight-type sensor with their
// height maps and contact masks into a dataset folder in the output folder
// (the ContactNet/TactileDepthNet report's TactileDataset layout: touchcloud/io/tactile_dataset.hpp),
// every fifth sample into validation/; the reference image with the first
// sample, dataset.yaml at the end.
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>

#include "touchcloud/file_write.hpp"
#include "touchcloud/io/tactile_dataset.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class TactileDatasetWriter final : public Stage {
  std::string folder_;
  double contact_threshold_mm_ = 0.05;
  long samples_ = 0, validation_ = 0;
  std::optional<io::TactileDatasetInfo> info_;

  void declare_parameters(ParameterSet& p) override {
    p.add("folder", folder_, std::string("tactile_dataset"))
        .output_file()
        .doc("dataset folder in the output folder: dataset.yaml, reference.png, train/ and validation/");
    p.add("contact_threshold_mm", contact_threshold_mm_, 0.05).unit("mm").above(0)
        .doc("recorded in dataset.yaml: the height above which the masks (and a reader without masks) say contact");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<MonoColourFramePtr>("image", "the tactile image");
    ports.input<HeightMapPtr>("height", "its height map (mm) and contact mask (e.g. gelsight_simulator.height_truth)");
    ports.optional_input<MonoColourFramePtr>("reference", "the no-contact image (written once)");
    ports.metric("samples_written", "samples", "samples written into the dataset").final();
    ports.metric("validation_samples", "samples", "of them, samples in the validation split").final();
    ports.artifact(ArtifactRole::dataset, "the dataset's images, height maps, contact masks and info file");
  }

  void write_image(RunContext& ctx, const cv::Mat& image, const std::string& path) {
    std::vector<std::uint8_t> bytes;
    const std::string extension = image.depth() == CV_32F ? ".tiff" : ".png";
    if (!cv::imencode(extension, image, bytes))
      throw RunError("OpenCV could not encode " + path + " (" + cv::typeToString(image.type()) + ")");
    write_file(ctx.output_path(folder_ + "/" + path),
               std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    ctx.artifact(ArtifactRole::dataset, folder_ + "/" + path, {{"dataset", folder_}});
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& image = io.input<MonoColourFramePtr>("image");
    const auto& height = io.input<HeightMapPtr>("height");
    if (!image || image->image.empty() || image->image.type() != CV_8UC3)
      throw InputError("input 'image': no 8-bit BGR tactile image");
    if (!height || height->height_mm.type() != CV_32FC1 || height->height_mm.size() != image->image.size())
      throw InputError("input 'height': no CV_32FC1 height map of the image's size (" +
                       std::to_string(image->image.cols) + " x " + std::to_string(image->image.rows) + " px)");
    if (!cv::checkRange(height->height_mm))
      throw InputError("input 'height': the height map of frame " + std::to_string(height->index) +
                       " holds NaN or infinity");
    io::TactileDatasetInfo info{image->sensor, image->image.cols, image->image.rows, height->mm_per_px,
                                height->gel_thickness_mm, contact_threshold_mm_};
    if (info_ && (info_->sensor != info.sensor || info_->width_px != info.width_px ||
                  info_->height_px != info.height_px || info_->mm_per_px != info.mm_per_px))
      throw InputError("input 'image' (frame " + std::to_string(image->index) + "): sensor '" + info.sensor +
                       "' at " + std::to_string(info.width_px) + " x " + std::to_string(info.height_px) +
                       " px differs from the earlier samples' ('" + info_->sensor + "'); a dataset has one sensor");
    info_ = info;
    if (samples_ == 0)
      if (const auto* r = io.optional_input<MonoColourFramePtr>("reference"); r && *r && !(*r)->image.empty())
        write_image(ctx, (*r)->image, io::kTactileDatasetReference);
    write_image(ctx, image->image, io::tactile_sample_path(samples_, "images"));
    write_image(ctx, height->height_mm, io::tactile_sample_path(samples_, "depths"));
    const cv::Mat mask = height->contact_mask.empty() ? cv::Mat(height->height_mm > contact_threshold_mm_)
                                                      : height->contact_mask;
    write_image(ctx, mask, io::tactile_sample_path(samples_, "masks"));
    validation_ += io::tactile_in_validation(samples_);
    ++samples_;
  }

  void on_finish(RunContext& ctx) override {
    if (!info_) return;
    write_file(ctx.output_path(folder_ + "/" + io::kTactileDatasetInfo), io::tactile_dataset_info_text(*info_));
    ctx.artifact(ArtifactRole::dataset, folder_ + "/" + io::kTactileDatasetInfo, {{"dataset", folder_}});
    ctx.metric("samples_written", static_cast<double>(samples_), "samples");
    ctx.metric("validation_samples", static_cast<double>(validation_), "samples");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::TactileDatasetWriter, "tactile_dataset_writer", writer,
                  "Writes GelSight-type images with height maps and contact masks into a dataset folder (80/20 split)")
