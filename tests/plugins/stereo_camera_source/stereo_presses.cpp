#include "stereo_presses.hpp"

#include <fstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "test_support.hpp"
#include "video_file.hpp"

namespace fs = std::filesystem;

namespace touchcloud::test {

std::vector<ViewPair> stereo_presses() {
  const fs::path root = source_dir() / "sample_clouds/colour_recording";
  const auto read = [&](const std::string& name) { return cv::imread((root / name).string(), cv::IMREAD_COLOR); };
  const ViewPair rest{read("reference_left.png"), read("reference_right.png")};
  const ViewPair press{read("press_left_0.png"), read("press_right_0.png")};
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 0, 0, 1, 8);  // 8 px down: another spot, same disparity
  ViewPair moved;
  cv::warpAffine(press.left, moved.left, shift, press.left.size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  cv::warpAffine(press.right, moved.right, shift, press.right.size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  return {rest, press, moved, press};
}

void write_side(const fs::path& dir, const std::string& side, const std::vector<cv::Mat>& frames,
                const std::vector<double>& timestamps_s) {
  fs::create_directories(dir);
  std::ofstream index(dir / (side + ".csv"));
  index << "index,timestamp_s,file\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::string name = side + "_" + std::to_string(k) + ".png";
    cv::imwrite((dir / name).string(), frames[k]);
    index << k << ',' << timestamps_s[k] << ',' << name << '\n';
  }
}

void write_video(const fs::path& file, const std::vector<cv::Mat>& frames, double fps) {
  if (!write_video_file(file, "FFV1", frames, fps)) throw std::runtime_error("cannot write " + file.string());
}

std::vector<cv::Mat> lefts(const std::vector<ViewPair>& pairs) {
  std::vector<cv::Mat> out;
  for (const auto& p : pairs) out.push_back(p.left);
  return out;
}

std::vector<cv::Mat> rights(const std::vector<ViewPair>& pairs) {
  std::vector<cv::Mat> out;
  for (const auto& p : pairs) out.push_back(p.right);
  return out;
}

std::vector<cv::Mat> side_by_side(const std::vector<ViewPair>& pairs) {
  std::vector<cv::Mat> out;
  for (const auto& p : pairs) {
    cv::Mat both;
    cv::hconcat(p.left, p.right, both);
    out.push_back(both);
  }
  return out;
}

}  // namespace touchcloud::test
