#include "touchcloud/learning/stereo_samples.hpp"

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/io/image_file.hpp"
#include "touchcloud/io/stereo_dataset.hpp"

namespace touchcloud::learning {

namespace fs = std::filesystem;

StereoSamples read_stereo_samples(const fs::path& index_file) {
  StereoSamples out;
  out.index_file = index_file;
  const fs::path folder = index_file.parent_path();
  if (index_file.filename() != io::kDatasetIndex)
    throw InputError(index_file.string() + ": not a dataset's " + io::kDatasetIndex);
  std::error_code ec;
  if (!fs::is_regular_file(index_file, ec)) throw InputError(index_file.string() + ": dataset index not found");
  const auto rows = io::read_dataset_index(folder);
  if (rows.empty()) throw InputError(index_file.string() + ": the dataset has no pairs (no rows after the header)");
  out.camera = io::read_rectified_camera(folder / io::kDatasetCamera);
  for (const auto& row : rows) {
    StereoSample s;
    s.index = row.index;
    s.where = index_file.string() + ":" + std::to_string(row.line);
    auto read = [&](io::DatasetFile file, int type) -> cv::Mat {
      const std::string& name = row.files[file];
      if (name.empty()) return {};
      const std::string what = s.where + ": " + io::dataset_column(file) + " file '" + name + "'";
      const cv::Mat image = read_image_file(folder / name, type == CV_8UC3 ? cv::IMREAD_COLOR : cv::IMREAD_UNCHANGED, what);
      if (image.type() != type)
        throw InputError(what + " is " + cv::typeToString(image.type()) + "; expected " + cv::typeToString(type));
      if (image.cols != out.camera.width_px || image.rows != out.camera.height_px)
        throw InputError(what + " is " + std::to_string(image.cols) + " x " + std::to_string(image.rows) +
                         " px; camera.yaml says " + std::to_string(out.camera.width_px) + " x " +
                         std::to_string(out.camera.height_px));
      return image;
    };
    s.left = read(io::kLeft, CV_8UC3);
    s.right = read(io::kRight, CV_8UC3);
    s.contact_mask = read(io::kContactMask, CV_8UC1);
    s.disparity_left_px = read(io::kDisparityLeft, CV_32FC1);
    s.valid_left = read(io::kValidLeft, CV_8UC1);
    if (s.disparity_left_px.empty() != s.valid_left.empty())
      throw InputError(s.where + ": disparity_left and valid_left come together");
    if (!s.disparity_left_px.empty() && !cv::checkRange(s.disparity_left_px))
      throw InputError(s.where + ": disparity_left holds NaN or infinity");
    out.samples.push_back(std::move(s));
  }
  return out;
}

}  // namespace touchcloud::learning
