#include "touchcloud/io/tactile_sample_files.hpp"

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/io/image_file.hpp"

namespace touchcloud::io {

cv::Mat read_dataset_image(const std::filesystem::path& file, int type, const TactileDatasetInfo& info,
                           const std::string& info_file) {
  const std::string name = "dataset file " + file.string();
  const cv::Mat image = type == CV_8UC3 ? read_colour_image_file(file, name) : read_image_file(file, cv::IMREAD_UNCHANGED, name);
  if (image.type() != type)
    throw InputError("dataset file " + file.string() + " is " + cv::typeToString(image.type()) + "; expected " +
                     cv::typeToString(type));
  if (image.cols != info.width_px || image.rows != info.height_px)
    throw InputError("dataset file " + file.string() + " is " + std::to_string(image.cols) + " x " +
                     std::to_string(image.rows) + " px; " + info_file + " says " + std::to_string(info.width_px) +
                     " x " + std::to_string(info.height_px));
  return image;
}

SampleTruth read_sample_truth(const TactileSample& s, const TactileDatasetInfo& info,
                              const std::string& info_file) {
  SampleTruth t;
  t.height_mm = read_dataset_image(s.depth, CV_32FC1, info, info_file);
  if (!cv::checkRange(t.height_mm))
    throw InputError("dataset file " + s.depth.string() + " holds NaN or infinity (heights in mm, never NaN)");
  t.contact_mask = s.mask.empty() ? cv::Mat(t.height_mm > info.contact_threshold_mm)
                                  : read_dataset_image(s.mask, CV_8UC1, info, info_file);
  return t;
}

}  // namespace touchcloud::io
