// Pixels whose colour is no shading (a marker dot's ink) left out of a
// field computed per pixel and filled from the pixels around them: first,
// along each row, the straight line between the kept pixels either side;
// then over-relaxed sweeps of the 4-neighbour mean (towards the harmonic
// fill), so a slope across a dot in any direction goes on as a plane would.
// A dot on a contact's rim so keeps the rim's values on either side, where a
// colour fitted across it gives a slope neither side has; and nothing is
// fitted per dot, so it is cheap (work in proportion to the pixels left out
// where the field has a value around them: a dot on flat gel costs a look).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

struct ExcludedPixels {
  cv::Mat mask;       // CV_8UC1, set: left out
  int window_px = 3;  // odd; a left-out blob is at most this wide (sets the sweeps)
};

// Reused between fills: the excluded pixels inside the image by colour
// (red-black) and on its border; those reached from a kept pixel with a value.
struct FillScratch {
  std::vector<int> red, black, edge, queue;
  std::vector<std::uint8_t> reached;
};

class ExcludedFill {
 public:
  // Each field (all CV_32FC1 or all CV_64FC1, continuous, the mask's size)
  // filled in place at the excluded pixels.
  void fill(const ExcludedPixels& excluded, std::initializer_list<cv::Mat*> fields);

 private:
  FillScratch scratch_;
};

}  // namespace touchcloud::imaging
