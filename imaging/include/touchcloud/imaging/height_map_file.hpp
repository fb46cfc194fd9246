// A height map as a 16-bit image file that any image tool opens: each
// sample is round(height / mm_per_count), so heights from 0 to 65535
// counts x mm_per_count fit (0.0001 mm per count: up to 6.55 mm, finer
// than any GelSight-type sensor resolves). A PNG carries its scale in a
// text chunk (keyword "touchcloud:mm_per_count", value the number), a
// TIFF only in what the caller records beside it (summary.json).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

inline constexpr const char* kHeightScaleKeyword = "touchcloud:mm_per_count";

// Why `path` cannot name a height map file (.png, .tif or .tiff), or nothing.
std::optional<std::string> height_map_path_problem(const std::string& path);

struct HeightMapFileSummary {
  long below_zero = 0;   // samples below 0 mm, written as 0 (integration noise beside the contact)
  long invalid = 0;      // samples marked invalid, written as 0
  double max_height_mm = 0;
};

// Writes `height_mm` (CV_32FC1; `valid` CV_8UC1 or empty) to `file`.
// InputError when a height exceeds the range (it names the height and the
// scale that would hold it); RunError when the file cannot be written.
HeightMapFileSummary write_height_map_file(const std::filesystem::path& file, const cv::Mat& height_mm,
                                           const cv::Mat& valid, double mm_per_count);

// The PNG's scale text chunk, or nothing when `file` has none.
std::optional<double> read_height_scale(const std::filesystem::path& file);

}  // namespace touchcloud::imaging
