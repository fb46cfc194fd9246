// The folder layout of a dense stereo dataset (the colour-pattern GelStereo):
// rectified pairs, simulated or recorded, with ground truth where there is
// some, so that training and evaluation read both alike.
//
//   DIR/index.csv    one row per pair; the first line names the columns:
//                    index,timestamp_s,left,right,disparity_left,valid_left,
//                    disparity_right,valid_right,depth_mm,depth_valid,contact_mask
//                    (file paths relative to DIR; an empty field: not recorded)
//   DIR/camera.yaml  the rectified camera of every pair (rectified_stereo.hpp)
//
// Images are PNG (8-bit BGR), masks PNG (8-bit, 255 = valid or in contact),
// disparity (px) and depth (mm) maps 32-bit float TIFF.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "touchcloud/types/rectified_stereo.hpp"

namespace touchcloud::io {

enum DatasetFile {
  kLeft, kRight, kDisparityLeft, kValidLeft, kDisparityRight, kValidRight, kDepthMm, kDepthValid, kContactMask,
  kDatasetFileCount
};

struct StereoDatasetRow {
  long index = 0;
  double timestamp_s = 0;
  std::array<std::string, kDatasetFileCount> files;  // relative to the folder; empty: absent
  int line = 0;                                      // in index.csv, from 1 (set when read)
};

// The column name of each file ("left", "disparity_left", ...).
const char* dataset_column(DatasetFile file);

inline constexpr const char* kDatasetIndex = "index.csv";
inline constexpr const char* kDatasetCamera = "camera.yaml";

std::string dataset_index_text(const std::vector<StereoDatasetRow>& rows);
// Reads DIR/index.csv: InputError "FILE:LINE: ..." for a malformed row, a row
// without left or right, or a path that leaves the folder.
std::vector<StereoDatasetRow> read_dataset_index(const std::filesystem::path& folder);

std::string rectified_camera_text(const RectifiedStereo& camera);
// InputError naming the file and the field.
RectifiedStereo read_rectified_camera(const std::filesystem::path& file);

}  // namespace touchcloud::io
