#include "touchcloud/imaging/marker_pair.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/imaging/picture_file.hpp"

namespace touchcloud::imaging {

namespace {
constexpr int kImageGap = 8, kLegend = 44, kRadius = 4;

cv::Mat as_bgr(const cv::Mat& image, const std::string& which) {
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw InputError("the " + which + " image is " + cv::typeToString(image.type()) + "; expected 8-bit grey or BGR");
  cv::Mat out;
  if (image.channels() == 1) cv::cvtColor(image, out, cv::COLOR_GRAY2BGR);
  else out = image.clone();
  return out;
}
}  // namespace

std::vector<std::size_t> lined_matches(std::size_t matches, std::size_t max_lines) {
  std::vector<std::size_t> lined;
  if (max_lines == 0) return lined;
  const std::size_t step = std::max<std::size_t>(1, (matches + max_lines - 1) / max_lines);
  for (std::size_t k = 0; k < matches && lined.size() < max_lines; k += step) lined.push_back(k);
  return lined;
}

cv::Scalar match_colour(std::size_t line) {
  const double golden = 0.6180339887498949;
  const double hue = 40 + 260 * std::fmod(static_cast<double>(line) * golden, 1.0);  // degrees
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue / 2, 230, 255)), bgr;  // OpenCV's 8-bit hue is degrees / 2
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const auto c = bgr.at<cv::Vec3b>(0, 0);
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

MarkerPairLayout marker_pair_layout(cv::Size size, int max_width_px) {
  MarkerPairLayout layout;
  layout.scale = std::min(1.0, static_cast<double>(max_width_px - kImageGap) / (2.0 * size.width));
  const int w = static_cast<int>(std::lround(size.width * layout.scale));
  layout.right_x = w + kImageGap;
  layout.legend_top = static_cast<int>(std::lround(size.height * layout.scale));
  return layout;
}

cv::Mat draw_marker_pair(const cv::Mat& left, const cv::Mat& right, const MarkerSet& markers,
                         const MarkerPairLayout& layout, std::size_t max_lines) {
  if (left.empty() || left.size() != right.size())
    throw InputError("the left and right images must be the same size, not " + std::to_string(left.cols) + " x " +
                     std::to_string(left.rows) + " and " + std::to_string(right.cols) + " x " +
                     std::to_string(right.rows) + " px");
  if (!markers.stereo()) throw InputError("the marker set is of one camera's image; a pair needs a stereo set");
  const int w = layout.right_x - kImageGap, h = layout.legend_top;
  cv::Mat picture(h + kLegend, layout.right_x + w, CV_8UC3, kPaper);
  for (int view = 0; view < 2; ++view) {
    cv::Mat scaled;
    cv::resize(as_bgr(view == 0 ? left : right, view == 0 ? "left" : "right"), scaled, {w, h}, 0, 0, cv::INTER_AREA);
    scaled.copyTo(picture(cv::Rect(view == 0 ? 0 : layout.right_x, 0, w, h)));
  }
  // Sub-pixel positions: drawn with 4 fractional bits.
  const auto fixed = [](cv::Point2d p) {
    return cv::Point(static_cast<int>(std::lround(p.x * 16)), static_cast<int>(std::lround(p.y * 16)));
  };
  const auto ring = [&](int view, const Marker& m, const cv::Scalar& colour, int thickness) {
    cv::circle(picture, fixed(layout.at(view, m.centre_px)), kRadius * 16, colour, thickness, cv::LINE_AA, 4);
  };
  std::vector<bool> matched_left(markers.left.size()), matched_right(markers.right.size());
  for (const MarkerMatch& m : markers.matches) {
    for (const auto& [i, list, view] : {std::tuple(m.left, &markers.left, "left"), std::tuple(m.right, &markers.right, "right")})
      if (i < 0 || static_cast<std::size_t>(i) >= list->size())
        throw InputError("a match names " + std::string(view) + " marker " + std::to_string(i) + " of " +
                         std::to_string(list->size()));
    matched_left[m.left] = matched_right[m.right] = true;
  }
  std::size_t unmatched[2] = {0, 0};
  for (int view = 0; view < 2; ++view) {
    const auto& list = view == 0 ? markers.left : markers.right;
    const auto& matched = view == 0 ? matched_left : matched_right;
    for (std::size_t i = 0; i < list.size(); ++i) {
      unmatched[view] += !matched[i];
      ring(view, list[i], matched[i] ? kMatched : kUnmatched, 1);
    }
  }
  const std::vector<std::size_t> lined = lined_matches(markers.matches.size(), max_lines);
  for (std::size_t k = 0; k < lined.size(); ++k) {
    const MarkerMatch& m = markers.matches[lined[k]];
    const cv::Scalar colour = match_colour(k);
    cv::line(picture, fixed(layout.at(0, markers.left[m.left].centre_px)),
             fixed(layout.at(1, markers.right[m.right].centre_px)), colour, 1, cv::LINE_AA, 4);
    ring(0, markers.left[m.left], colour, 2);
    ring(1, markers.right[m.right], colour, 2);
  }

  // Legend: what the colours mean, with the counts.
  const int y = h + 18;
  int x = 8;
  const auto key = [&](const cv::Scalar& colour, const std::string& text) {
    cv::circle(picture, {x + kRadius, y - 4}, kRadius, colour, 2, cv::LINE_AA);
    put_text(picture, text, {x + 2 * kRadius + 6, y}, kTextColour);
    x += 2 * kRadius + 6 + text_width(text) + 18;
  };
  key(kMatched, std::to_string(markers.matches.size()) + " left-right matches");
  key(match_colour(0), std::to_string(lined.size()) + " of them joined by lines, a colour each");
  key(kUnmatched, "unmatched: " + std::to_string(unmatched[0]) + " left, " + std::to_string(unmatched[1]) + " right");
  put_text(picture, "left image (" + std::to_string(markers.left.size()) + " markers detected) | right image (" +
                        std::to_string(markers.right.size()) + ")",
           {8, y + 18}, kTextColour);
  return picture;
}

}  // namespace touchcloud::imaging
