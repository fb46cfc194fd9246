// stereo_dataset_writer: rectified colour pairs, with their ground truth when
// wired, into a dataset folder in the output folder (layout:
// touchcloud/io/stereo_dataset.hpp), one row per call; the index and the
// camera file are written at the end.
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>

#include "touchcloud/file_write.hpp"
#include "touchcloud/io/stereo_dataset.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class StereoDatasetWriter final : public Stage {
  std::string folder_;
  std::vector<io::StereoDatasetRow> rows_;
  std::optional<RectifiedStereo> camera_;

  void declare_parameters(ParameterSet& p) override {
    p.add("folder", folder_, std::string("dataset"))
        .output_file()
        .doc("dataset folder in the output folder: index.csv, camera.yaml, pairs/ and truth/");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<ColourStereoFramePtr>("frame", "rectified colour pair");
    ports.optional_input<DenseMapsPtr>("truth", "its ground truth (disparities, depth, contact mask)");
  }

  // Encodes `image` as `extension` and writes it (every write checked); the
  // row's field gets the path relative to the folder.
  void write_image(RunContext& ctx, const cv::Mat& image, const std::string& name, std::string& field) {
    if (image.empty()) return;
    std::vector<std::uint8_t> bytes;
    const std::string extension = image.depth() == CV_32F ? ".tiff" : ".png";
    if (!cv::imencode(extension, image, bytes))
      throw RunError("OpenCV could not encode " + name + extension + " (" + cv::typeToString(image.type()) + ")");
    field = name + extension;
    write_file(ctx.output_path(folder_ + "/" + field), std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& frame = io.input<ColourStereoFramePtr>("frame");
    if (!frame || frame->left.empty() || frame->right.empty()) throw InputError("input 'frame': no colour pair");
    if (camera_ && (camera_->width_px != frame->camera.width_px || camera_->height_px != frame->camera.height_px ||
                    camera_->fx_px != frame->camera.fx_px || camera_->baseline_mm != frame->camera.baseline_mm))
      throw InputError("input 'frame' (frame " + std::to_string(frame->index) +
                       "): its rectified camera differs from the earlier pairs'; a dataset has one camera");
    camera_ = frame->camera;
    io::StereoDatasetRow row;
    row.index = static_cast<long>(rows_.size());
    row.timestamp_s = frame->timestamp_s;
    char stem[32];
    std::snprintf(stem, sizeof stem, "%06ld", row.index);
    const std::string pair = std::string("pairs/") + stem + "_", truth = std::string("truth/") + stem + "_";
    write_image(ctx, frame->left, pair + "left", row.files[io::kLeft]);
    write_image(ctx, frame->right, pair + "right", row.files[io::kRight]);
    if (const auto* t = io.optional_input<DenseMapsPtr>("truth"); t && *t) {
      const DenseMaps& m = **t;
      const std::pair<const cv::Mat*, io::DatasetFile> maps[] = {
          {&m.disparity_left_px, io::kDisparityLeft}, {&m.valid_left, io::kValidLeft},
          {&m.disparity_right_px, io::kDisparityRight}, {&m.valid_right, io::kValidRight},
          {&m.depth_mm, io::kDepthMm}, {&m.depth_valid, io::kDepthValid}, {&m.contact_mask, io::kContactMask}};
      for (const auto& [map, file] : maps) write_image(ctx, *map, truth + io::dataset_column(file), row.files[file]);
    }
    rows_.push_back(row);
  }

  void on_finish(RunContext& ctx) override {
    if (rows_.empty()) return;
    write_file(ctx.output_path(folder_ + "/" + io::kDatasetIndex), io::dataset_index_text(rows_));
    write_file(ctx.output_path(folder_ + "/" + io::kDatasetCamera), io::rectified_camera_text(*camera_));
    ctx.metric("pairs_written", static_cast<double>(rows_.size()), "pairs");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StereoDatasetWriter, "stereo_dataset_writer", writer,
                  "Writes rectified colour pairs and their ground truth into a dataset folder (PNG, float TIFF, index.csv)")
