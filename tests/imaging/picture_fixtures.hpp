// Small hand-made inputs of the pictures (map_pair.hpp, marker_pair.hpp)
// whose every drawn colour and place is known: for the drawing's tests and
// the picture stages' alike.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/map_pair.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::test {

// 40 x 30 px: value x at column x, all valid; the contact is the rectangle
// of columns 20..29, rows 10..19.
inline imaging::MapView ramp(const std::string& title) {
  imaging::MapView m;
  m.values.create(30, 40, CV_32FC1);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) m.values.at<float>(y, x) = static_cast<float>(x);
  m.valid = cv::Mat(30, 40, CV_8UC1, cv::Scalar(255));
  m.contact_mask = cv::Mat::zeros(30, 40, CV_8UC1);
  m.contact_mask(cv::Rect(20, 10, 10, 10)).setTo(255);
  m.title = title;
  return m;
}

// The grey of the 64 x 48 px pair three_and_two() is drawn on.
inline const cv::Vec3b kPairGrey(200, 200, 200);

// Three markers found left and two right, two of them matched.
inline MarkerSet three_and_two() {
  MarkerSet s;
  s.left = {{{10, 10}, -1, 1}, {{30, 20}, -1, 1}, {{50, 36}, -1, 1}};
  s.right = {{{8, 10}, -1, 1}, {{27, 20}, -1, 1}};
  s.matches = {{0, 0, 0}, {1, 1, 1}};  // left marker 2 has no match
  return s;
}

}  // namespace touchcloud::test
