// Pixels whose colour is no shading (a marker dot's ink) left out of a
// field computed per pixel and filled from the pixels around them: from the
// edge inwards (each pass, an excluded pixel next to known ones takes their
// mean), then smoothed towards the harmonic fill (Gauss-Seidel sweeps of the
// 4-neighbour mean), which carries a slope across a dot as a plane would. A
// dot on a contact's rim so keeps the rim's values on either side, where a
// colour fitted across it gives a slope neither side has; and nothing is
// fitted per dot, so it is cheap.
#pragma once

#include <initializer_list>
#include <vector>

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

struct ExcludedPixels {
  cv::Mat mask;       // CV_8UC1, set: left out
  int window_px = 3;  // odd; a left-out blob is at most this wide (the passes inwards: half of it)
};

class ExcludedFill {
 public:
  // Each field (CV_32FC1 or CV_64FC1, the mask's size) filled in place at
  // the excluded pixels; one farther than window_px / 2 from a kept pixel
  // starts from 0.
  void fill(const ExcludedPixels& excluded, std::initializer_list<cv::Mat*> fields);

 private:
  cv::Mat known_;                 // scratch, reused
  std::vector<cv::Point> left_;
};

}  // namespace touchcloud::imaging
