// A tiny seeded tactile dataset for the GelSight-type networks' tests:
// COUNT samples of 64 x 48 px (0.06 mm/px), each a ball of 2 mm radius
// pressed 0.04 x i mm deep (sample 0: no contact) at a place that moves with
// i, shaded as the sensor's three coloured lights would shade it (Lambert),
// with its height map and contact mask (height > 0.05 mm). Written in the
// dataset layout (touchcloud/io/tactile_dataset.hpp) with OpenCV only: no
// torch; every fifth sample lands in validation/.
#pragma once

#include <cmath>
#include <filesystem>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "test_support.hpp"
#include "touchcloud/io/tactile_dataset.hpp"

namespace touchcloud::test::tiny_tactile {

inline constexpr int kWidth = 64, kHeight = 48;
inline constexpr double kMmPerPx = 0.06;

struct Sample {
  cv::Mat image, height_mm, mask;  // CV_8UC3, CV_32FC1, CV_8UC1
};

inline cv::Mat reference() { return cv::Mat(kHeight, kWidth, CV_8UC3, cv::Scalar(100, 100, 100)); }

inline Sample sample(int i) {
  const double radius = 2.0, depth = 0.04 * i;
  const double cu = 20 + (7 * i) % 24, cv_ = 16 + (5 * i) % 16;
  const double lights[3][3] = {{0.82, 0, 0.57}, {-0.41, 0.71, 0.57}, {-0.41, -0.71, 0.57}};  // B, G, R
  Sample s{reference(), cv::Mat::zeros(kHeight, kWidth, CV_32FC1), cv::Mat()};
  for (int v = 0; v < kHeight; ++v)
    for (int u = 0; u < kWidth; ++u) {
      const double x = (u - cu) * kMmPerPx, y = (v - cv_) * kMmPerPx, r2 = x * x + y * y;
      const double h = depth - (radius - std::sqrt(std::max(0.0, radius * radius - r2)));
      if (h <= 0 || r2 >= radius * radius) continue;
      s.height_mm.at<float>(v, u) = static_cast<float>(h);
      const double z = std::sqrt(radius * radius - r2);
      const double n[3] = {x / radius, y / radius, z / radius};  // the ball's normal
      for (int k = 0; k < 3; ++k) {
        const double shade = lights[k][0] * n[0] + lights[k][1] * n[1] + lights[k][2] * n[2] - lights[k][2];
        s.image.at<cv::Vec3b>(v, u)[k] = cv::saturate_cast<std::uint8_t>(100 + 150 * shade);
      }
    }
  s.mask = s.height_mm > 0.05;
  return s;
}

// Writes `count` samples (and reference.png, dataset.yaml) into `folder`; returns its dataset.yaml.
inline std::filesystem::path write(const std::filesystem::path& folder, int count) {
  for (const char* split : {"train", "validation"})
    for (const char* kind : {"images", "depths", "masks"}) std::filesystem::create_directories(folder / split / kind);
  cv::imwrite((folder / io::kTactileDatasetReference).string(), reference());
  for (int i = 0; i < count; ++i) {
    const Sample s = sample(i);
    cv::imwrite((folder / io::tactile_sample_path(i, "images")).string(), s.image);
    cv::imwrite((folder / io::tactile_sample_path(i, "depths")).string(), s.height_mm);
    cv::imwrite((folder / io::tactile_sample_path(i, "masks")).string(), s.mask);
  }
  io::TactileDatasetInfo info{"gelsight_mini", kWidth, kHeight, kMmPerPx, 2.5, 0.05};
  write_file(folder / io::kTactileDatasetInfo, io::tactile_dataset_info_text(info));
  return folder / io::kTactileDatasetInfo;
}

}  // namespace touchcloud::test::tiny_tactile
