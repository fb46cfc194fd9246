// stereo_dataset_reader: one rectified colour pair per call from a dataset
// folder (layout: touchcloud/io/stereo_dataset.hpp), simulated or recorded,
// with its ground truth when the folder has some. The index, the camera and
// the presence of every listed file are checked before the run starts.
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>

#include "touchcloud/io/stereo_dataset.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/path_text.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud {

// Recorded in summary.json's versions when this plugin is loaded.
namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

namespace fs = std::filesystem;

class StereoDatasetReader final : public Stage {
  std::string index_;
  std::string folder_;  // the index's folder
  // Read at check.
  std::vector<io::StereoDatasetRow> rows_;
  RectifiedStereo camera_;
  std::size_t next_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("index", index_, std::string())
        .input_file()
        .doc("the dataset's index.csv; its folder holds camera.yaml and the files the index lists");
  }

  void declare_ports(PortSet& ports) override {
    ports.output<ColourStereoFramePtr>("frame", "the next row's rectified colour pair (pose unknown: identity)");
    ports.output<DenseMapsPtr>("truth", "its ground truth (the row must list it)");
  }

  std::string where(const io::StereoDatasetRow& row) const {
    return index_ + ":" + std::to_string(row.line);
  }

  void on_check(RunContext&) override {
    folder_ = fs::path(index_).parent_path().string();
    if (fs::path(index_).filename() != io::kDatasetIndex)
      throw ParameterError("index", "'" + index_ + "' is not a dataset's " + io::kDatasetIndex);
    try {
      rows_ = io::read_dataset_index(folder_);
      camera_ = io::read_rectified_camera(fs::path(folder_) / io::kDatasetCamera);
    } catch (const InputError& e) {
      throw ParameterError("index", e.what());
    }
    std::error_code ec;
    for (const auto& row : rows_)
      for (int f = 0; f < io::kDatasetFileCount; ++f)
        if (!row.files[f].empty() && !fs::is_regular_file(fs::path(folder_) / row.files[f], ec))
          throw ParameterError("index", where(row) + ": " + io::dataset_column(static_cast<io::DatasetFile>(f)) +
                                             " file '" + row.files[f] + "' is missing");
  }

  cv::Mat read(const io::StereoDatasetRow& row, io::DatasetFile file, int type) const {
    const std::string& name = row.files[file];
    cv::Mat image = cv::imread((fs::path(folder_) / name).string(), type == CV_8UC3 ? cv::IMREAD_COLOR : cv::IMREAD_UNCHANGED);
    const std::string what = where(row) + ": " + io::dataset_column(file) + " file '" + name + "'";
    if (image.empty()) throw InputError(what + " cannot be read (unreadable or not an image OpenCV knows)");
    if (image.type() != type)
      throw InputError(what + " is " + cv::typeToString(image.type()) + "; expected " + cv::typeToString(type));
    if (image.cols != camera_.width_px || image.rows != camera_.height_px)
      throw InputError(what + " is " + std::to_string(image.cols) + " x " + std::to_string(image.rows) +
                       " px; camera.yaml says " + std::to_string(camera_.width_px) + " x " +
                       std::to_string(camera_.height_px));
    return image;
  }

  cv::Mat read_if_listed(const io::StereoDatasetRow& row, io::DatasetFile file, int type) const {
    return row.files[file].empty() ? cv::Mat() : read(row, file, type);
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    if (next_ >= rows_.size())
      throw InputError("dataset " + folder_ + " has " + std::to_string(rows_.size()) + " pairs; pair " +
                       std::to_string(next_ + 1) + " was asked for");
    const io::StereoDatasetRow& row = rows_[next_++];
    if (io.wants("frame")) {
      auto frame = std::make_shared<ColourStereoFrame>();
      frame->left = read(row, io::kLeft, CV_8UC3);
      frame->right = read(row, io::kRight, CV_8UC3);
      frame->camera = camera_;
      frame->timestamp_s = row.timestamp_s;
      frame->index = row.index;
      io.output<ColourStereoFramePtr>("frame", std::move(frame));
    }
    if (io.wants("truth")) {
      if (row.files[io::kDisparityLeft].empty() && row.files[io::kDepthMm].empty() && row.files[io::kContactMask].empty())
        throw InputError(where(row) + ": output 'truth' is read, but this row lists no ground truth");
      auto truth = std::make_shared<DenseMaps>();
      truth->disparity_left_px = read_if_listed(row, io::kDisparityLeft, CV_32FC1);
      truth->valid_left = read_if_listed(row, io::kValidLeft, CV_8UC1);
      truth->disparity_right_px = read_if_listed(row, io::kDisparityRight, CV_32FC1);
      truth->valid_right = read_if_listed(row, io::kValidRight, CV_8UC1);
      truth->depth_mm = read_if_listed(row, io::kDepthMm, CV_32FC1);
      truth->depth_valid = read_if_listed(row, io::kDepthValid, CV_8UC1);
      truth->contact_mask = read_if_listed(row, io::kContactMask, CV_8UC1);
      if (truth->disparity_left_px.empty() != truth->valid_left.empty() ||
          truth->disparity_right_px.empty() != truth->valid_right.empty() ||
          truth->depth_mm.empty() != truth->depth_valid.empty())
        throw InputError(where(row) + ": every disparity or depth map needs its validity mask, and every mask its map");
      for (const cv::Mat* m : {&truth->disparity_left_px, &truth->disparity_right_px, &truth->depth_mm})
        if (!m->empty() && !cv::checkRange(*m))
          throw InputError(where(row) + ": a disparity or depth map holds NaN or infinity; invalid pixels hold 0 "
                                        "and 0 in their mask");
      truth->camera = camera_;
      truth->timestamp_s = row.timestamp_s;
      truth->index = row.index;
      io.output<DenseMapsPtr>("truth", std::move(truth));
    }
    ctx.metric("pairs_read", static_cast<double>(next_), "pairs");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StereoDatasetReader, "stereo_dataset_reader", source,
                  "Reads rectified colour pairs, and their ground truth where listed, from a dataset folder")
