// A small tactile dataset written by tactile_dataset_writer: `count` seeded
// 32 x 24 samples (random image, a height bump whose depth grows with the
// sample, its mask), with a reference image.
#pragma once

#include <random>

#include <opencv2/core.hpp>

#include "stage_harness.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud::test {

struct TactileSampleData {
  MonoColourFramePtr image;
  HeightMapPtr height;
};

inline TactileSampleData tactile_sample(int i) {
  std::mt19937 rng(100 + i);
  auto image = std::make_shared<MonoColourFrame>();
  image->image = cv::Mat(24, 32, CV_8UC3);
  for (int v = 0; v < 24; ++v)
    for (int u = 0; u < 32; ++u) image->image.at<cv::Vec3b>(v, u) = cv::Vec3b(rng() % 256, rng() % 256, rng() % 256);
  image->sensor = "gelsight_mini";
  image->mm_per_px = 0.06;
  image->index = i;
  auto height = std::make_shared<HeightMap>();
  height->height_mm = cv::Mat::zeros(24, 32, CV_32FC1);
  for (int v = 0; v < 24; ++v)
    for (int u = 0; u < 32; ++u)
      height->height_mm.at<float>(v, u) =
          std::max(0.0f, 0.1f * (i + 1) - 0.01f * float((u - 16) * (u - 16) + (v - 12) * (v - 12)));
  height->valid = cv::Mat(24, 32, CV_8UC1, cv::Scalar(255));
  height->contact_mask = height->height_mm > 0.05;
  height->mm_per_px = 0.06;
  height->gel_thickness_mm = 2.5;
  height->index = i;
  return {image, height};
}

inline MonoColourFramePtr tactile_reference() {
  auto f = std::make_shared<MonoColourFrame>();
  f->image = cv::Mat(24, 32, CV_8UC3, cv::Scalar(90, 100, 110));
  f->sensor = "gelsight_mini";
  return f;
}

// Writes `count` samples into dir/tactile_dataset; returns its dataset.yaml.
inline std::filesystem::path write_tactile_dataset(const TempDir& dir, int count) {
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  StageHarness writer("tactile_dataset_writer", {}, "write", settings);
  writer.configure();
  for (int i = 0; i < count; ++i) {
    const auto s = tactile_sample(i);
    writer.process({{"image", s.image}, {"height", s.height}, {"reference", tactile_reference()}}, {});
  }
  writer.finish();
  return dir / "tactile_dataset" / "dataset.yaml";
}

}  // namespace touchcloud::test
