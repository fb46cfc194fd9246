// A dataset folder of two small seeded pairs (the second with ground truth),
// written by stereo_dataset_writer: shared by the writer's and the reader's tests.
#pragma once

#include <opencv2/core.hpp>

#include "stage_harness.hpp"
#include "test_support.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud::test::dataset {

inline RectifiedStereo camera() {
  RectifiedStereo c;
  c.width_px = 64;
  c.height_px = 48;
  c.fx_px = c.fy_px = 80.5;
  c.cx_left_px = c.cx_right_px = 31.5;
  c.cy_px = 23.5;
  c.baseline_mm = 30;
  return c;
}

inline ColourStereoFramePtr frame(int seed) {
  auto f = std::make_shared<ColourStereoFrame>();
  cv::theRNG().state = static_cast<std::uint64_t>(seed);
  f->left = cv::Mat(48, 64, CV_8UC3);
  f->right = cv::Mat(48, 64, CV_8UC3);
  cv::randu(f->left, 0, 256);
  cv::randu(f->right, 0, 256);
  f->camera = camera();
  f->timestamp_s = seed / 30.0;
  return f;
}

inline DenseMapsPtr truth() {
  auto t = std::make_shared<DenseMaps>();
  t->disparity_left_px = cv::Mat(48, 64, CV_32FC1);
  cv::randu(t->disparity_left_px, 10.0, 20.0);
  t->valid_left = cv::Mat(48, 64, CV_8UC1, cv::Scalar(255));
  t->valid_left.colRange(0, 5).setTo(0);
  t->disparity_left_px.colRange(0, 5).setTo(0);
  t->depth_mm = t->disparity_left_px * 3.25f;
  t->depth_valid = t->valid_left.clone();
  t->contact_mask = cv::Mat(48, 64, CV_8UC1, cv::Scalar(0));
  t->contact_mask(cv::Rect(20, 10, 8, 8)).setTo(255);
  t->camera = camera();
  return t;
}

inline bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Writes two pairs (the second with truth) into DIR/data.
inline void write_dataset(const std::filesystem::path& dir, bool with_truth) {
  RunSettings settings;
  settings.staging_dir = dir;
  settings.quiet = true;
  StageHarness w("stereo_dataset_writer", {{"folder", std::string("data")}}, "write", settings);
  w.configure();
  w.process({{"frame", frame(1)}}, {});
  std::map<std::string, std::any> second{{"frame", frame(2)}};
  if (with_truth) second["truth"] = truth();
  w.process(second, {});
  w.finish();
}

inline std::string index_of(const TempDir& dir) { return (dir / "data" / "index.csv").string(); }

}  // namespace touchcloud::test::dataset
