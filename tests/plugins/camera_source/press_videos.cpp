#include "press_videos.hpp"

#include <algorithm>

#include <opencv2/imgcodecs.hpp>

#include "test_support.hpp"
#include "video_file.hpp"

namespace fs = std::filesystem;

namespace touchcloud::test {

std::vector<cv::Mat> press_frames() {
  const fs::path root = source_dir() / "sample_clouds/tactile_nets_sample";
  std::vector<fs::path> files;
  for (const char* split : {"train", "validation"})
    for (const auto& e : fs::directory_iterator(root / split / "images")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  files.insert(files.begin(), root / "reference.png");
  std::vector<cv::Mat> frames;
  for (const auto& f : files) frames.push_back(cv::imread(f.string(), cv::IMREAD_COLOR));
  return frames;
}

void write_frame_files(const fs::path& dir, const std::vector<cv::Mat>& frames) {
  fs::create_directories(dir);
  for (std::size_t k = 0; k < frames.size(); ++k)
    cv::imwrite((dir / ("frame_" + std::to_string(k) + ".png")).string(), frames[k]);
}

bool write_video(const fs::path& file, const std::string& fourcc, const std::vector<cv::Mat>& frames) {
  return write_video_file(file, fourcc, frames, 25);
}

}  // namespace touchcloud::test
