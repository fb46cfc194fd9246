// An estimated map (disparity in px, height in mm) beside its ground truth,
// on one colour scale, with the colour bar and a legend below: what a person
// compares at a glance, where the numbers in summary.json say how much.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

// One map as drawn: its values, which of them hold one, and where the gel
// touches (outlined; empty: no outline).
struct MapView {
  cv::Mat values;        // CV_32FC1
  cv::Mat valid;         // CV_8UC1, nonzero where `values` holds a value
  cv::Mat contact_mask;  // CV_8UC1 or empty
  std::string title;     // drawn above the map
};

// Values from `low` to `high` onto viridis (OpenCV's COLORMAP_VIRIDIS);
// values beyond the ends take the end colours.
struct ColourScale {
  double low = 0, high = 1;
  std::string unit;  // "px", "mm"
  // The colour (BGR) of `value`.
  cv::Vec3b colour(double value) const;
  // The 8-bit index into the colour map of `value`.
  int index(double value) const;
};

// The range of `map`'s valid values; one unit wide around them when they are
// all the same. InputError when it has no valid value.
ColourScale scale_of(const MapView& map, const std::string& unit);

// A pixel without a value, and the outline of the contact region.
inline const cv::Vec3b kNoValue{128, 128, 128};
inline const cv::Vec3b kContactOutline{255, 255, 255};

// The maps side by side (the size of `right`, CV_32FC1 with CV_8UC1 masks; maps
// narrower than 320 px drawn 2x or more, each pixel a block), titled, on
// `scale`, with the colour bar and legend below. 8-bit BGR.
cv::Mat draw_map_pair(const MapView& left, const MapView& right, const ColourScale& scale);

// One map alone (an estimate without a truth), drawn as draw_map_pair draws
// each of its maps, its contact mask outlined.
cv::Mat draw_map(const MapView& map, const ColourScale& scale);

// Where map pixel (x, y) of the left (0) or right (1) map lies in the
// picture draw_map_pair (or draw_map, which 0) makes for maps of `size`: its
// block's top-left corner.
cv::Point map_pixel_in_picture(cv::Size size, int which, int x, int y);

}  // namespace touchcloud::imaging
