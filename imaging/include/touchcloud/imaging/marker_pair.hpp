// A stereo pair side by side with its markers drawn: every matched marker
// a green circle, every unmatched one red, and a few matches (evenly spread
// over them) joined across the pair by lines, each in a colour of its own;
// a legend below. Lines for all of a gel's thousand-odd matches would hide
// the images.
#pragma once

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::imaging {

// The matches joined by lines take hues from 40 to 300 degrees (golden-ratio
// steps), so none is the unmatched markers' red.
cv::Scalar match_colour(std::size_t line);
inline const cv::Scalar kMatched{0, 190, 0};
inline const cv::Scalar kUnmatched{0, 0, 255};

// Which of `matches` matches are joined by lines: at most `max_lines`,
// every k-th from the first.
std::vector<std::size_t> lined_matches(std::size_t matches, std::size_t max_lines);

struct MarkerPairLayout {
  double scale = 1;      // picture pixels per image pixel
  int right_x = 0;       // where the right image starts in the picture
  int legend_top = 0;    // below the images
  // Where image point `p` of the left (0) or right (1) view lies in the picture.
  cv::Point2d at(int view, const Eigen::Vector2d& p) const {
    return {(view == 0 ? 0 : right_x) + p.x() * scale, p.y() * scale};
  }
};

// The layout for images of `size` drawn at most `max_width_px` wide in all.
MarkerPairLayout marker_pair_layout(cv::Size size, int max_width_px);

// `left` and `right` (the same size; 8-bit grey or BGR) with `markers` (a
// stereo set) drawn on them, lines for lined_matches(.., max_lines).
// InputError on other images, a set of one view or a match naming no marker.
cv::Mat draw_marker_pair(const cv::Mat& left, const cv::Mat& right, const MarkerSet& markers,
                         const MarkerPairLayout& layout, std::size_t max_lines);

}  // namespace touchcloud::imaging
