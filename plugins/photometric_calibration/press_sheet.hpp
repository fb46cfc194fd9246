// The contact sheet of a ball-press calibration: every image, half size, in
// rows of four, its circle drawn (green found, blue corrected, a red cross
// refused or skipped) over its name and what became of it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/ball_press.hpp"

namespace touchcloud::photometric {

struct SheetTile {
  cv::Mat image;  // CV_8UC3
  std::string name;
  std::string status;  // "found", "corrected", "refused: ...", "skipped", with "held out" where it is
  std::optional<imaging::ContactCircle> circle;
  bool corrected = false;
};

cv::Mat press_sheet(const std::vector<SheetTile>& tiles);

}  // namespace touchcloud::photometric
