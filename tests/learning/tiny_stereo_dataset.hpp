// A tiny seeded dense stereo dataset for the network tests: PAIRS pairs of
// SIZE x SIZE px of one gel's texture whose right view is the left one moved
// by 3 px, and by 5 px inside a square "contact" region (listed as the
// contact mask, and as the left disparity truth), where the press also moves
// the pattern by 1 px in the left view, so that its difference to the rest
// pair (no contact) shows the region. Written in the dataset layout
// (touchcloud/io/stereo_dataset.hpp) with OpenCV only: no torch.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "test_support.hpp"
#include "touchcloud/io/stereo_dataset.hpp"

namespace touchcloud::test::tiny {

inline RectifiedStereo camera(int size) {
  RectifiedStereo c;
  c.width_px = c.height_px = size;
  c.fx_px = c.fy_px = 80;
  c.cx_left_px = c.cx_right_px = c.cy_px = (size - 1) / 2.0;
  c.baseline_mm = 30;
  return c;
}

struct Pair {
  cv::Mat left, right, contact, disparity;
};

// Pair `k`: the gel's smoothed random texture (the same for every k), the
// contact square at a position that depends on k; `rest`: no contact
// square (3 px everywhere, the pattern unmoved).
inline Pair pair(int k, int size, bool rest = false) {
  cv::RNG rng(1000);
  cv::Mat noise(size, size + 17, CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(3, 3), 0.8);
  Pair p;
  p.contact = cv::Mat(size, size, CV_8UC1, cv::Scalar(0));
  const int side = size / 4, x0 = size / 4 + (k % 3) * size / 8, y0 = size / 4 + (k % 2) * size / 8;
  if (!rest) p.contact(cv::Rect(x0, y0, side, side)).setTo(255);
  p.disparity = cv::Mat(size, size, CV_32FC1, cv::Scalar(3.0f));
  p.disparity.setTo(5.0f, p.contact);
  // Left x shows the pattern at x (+ 1 in contact); right x shows left x + d(x)
  // (a left pixel x matches the right x - d).
  p.left = cv::Mat(size, size, CV_8UC3);
  p.right = cv::Mat(size, size, CV_8UC3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const int moved = p.contact.at<std::uint8_t>(y, x) ? 1 : 0;
      p.left.at<cv::Vec3b>(y, x) = noise.at<cv::Vec3b>(y, 8 + x + moved);
      const bool in_contact = p.contact.at<std::uint8_t>(y, std::min(size - 1, x + 3));
      const int d = in_contact ? 5 : 3;
      p.right.at<cv::Vec3b>(y, x) = noise.at<cv::Vec3b>(y, std::min(size + 16, 8 + x + d + (in_contact ? 1 : 0)));
    }
  return p;
}

// Writes `pairs` pairs into `folder` (created); returns its index.csv.
inline std::filesystem::path write(const std::filesystem::path& folder, int pairs, int size, bool with_masks = true) {
  std::filesystem::create_directories(folder);
  std::vector<io::StereoDatasetRow> rows;
  for (int k = 0; k < pairs; ++k) {
    const Pair p = pair(k, size);
    io::StereoDatasetRow row;
    row.index = k;
    row.timestamp_s = k / 30.0;
    const std::string n = std::to_string(k);
    auto put = [&](const cv::Mat& m, const std::string& name, io::DatasetFile f) {
      cv::imwrite((folder / name).string(), m);
      row.files[f] = name;
    };
    put(p.left, "left_" + n + ".png", io::kLeft);
    put(p.right, "right_" + n + ".png", io::kRight);
    if (with_masks) put(p.contact, "contact_" + n + ".png", io::kContactMask);
    put(p.disparity, "disparity_" + n + ".tiff", io::kDisparityLeft);
    put(cv::Mat(size, size, CV_8UC1, cv::Scalar(255)), "valid_" + n + ".png", io::kValidLeft);
    rows.push_back(row);
  }
  write_file(folder / io::kDatasetIndex, io::dataset_index_text(rows));
  write_file(folder / io::kDatasetCamera, io::rectified_camera_text(camera(size)));
  return folder / io::kDatasetIndex;
}

// The gel at rest: one pair, no contact, no ground truth, in `folder`
// (created); returns its index.csv.
inline std::filesystem::path write_rest(const std::filesystem::path& folder, int size) {
  std::filesystem::create_directories(folder);
  const Pair p = pair(99, size, true);
  io::StereoDatasetRow row;
  row.index = 0;
  cv::imwrite((folder / "left.png").string(), p.left);
  cv::imwrite((folder / "right.png").string(), p.right);
  row.files[io::kLeft] = "left.png";
  row.files[io::kRight] = "right.png";
  write_file(folder / io::kDatasetIndex, io::dataset_index_text({row}));
  write_file(folder / io::kDatasetCamera, io::rectified_camera_text(camera(size)));
  return folder / io::kDatasetIndex;
}

}  // namespace touchcloud::test::tiny
