#include "touchcloud/imaging/map_pair.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/imaging/picture_file.hpp"

namespace touchcloud::imaging {

namespace {

constexpr int kMargin = 10, kGap = 12, kTitle = 22, kBar = 14, kMinPanelWidth = 320;

// OpenCV's viridis, index 0..255 -> BGR.
const cv::Mat& viridis() {
  static const cv::Mat lut = [] {
    cv::Mat ramp(1, 256, CV_8UC1), out;
    for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::applyColorMap(ramp, out, cv::COLORMAP_VIRIDIS);
    return out;
  }();
  return lut;
}

int block_of(cv::Size size) { return std::max(1, (kMinPanelWidth + size.width - 1) / size.width); }

std::string number(double v, const std::string& unit) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4g %s", v, unit.c_str());
  return buf;
}

// One map in colour: each value's colour, grey where none, the contact outlined.
cv::Mat colour_map(const MapView& m, const ColourScale& scale, int block) {
  cv::Mat out(m.values.size(), CV_8UC3);
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x)
      out.at<cv::Vec3b>(y, x) = m.valid.at<std::uint8_t>(y, x) ? scale.colour(m.values.at<float>(y, x)) : kNoValue;
  cv::resize(out, out, {}, block, block, cv::INTER_NEAREST);
  if (!m.contact_mask.empty()) {
    cv::Mat mask;
    cv::resize(m.contact_mask, mask, {}, block, block, cv::INTER_NEAREST);
    std::vector<std::vector<cv::Point>> outline;
    cv::findContours(mask > 0, outline, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    cv::drawContours(out, outline, -1, cv::Scalar(kContactOutline), 1);
  }
  return out;
}

void check(const MapView& m, cv::Size size, const std::string& which) {
  const auto size_text = [](cv::Size s) { return std::to_string(s.width) + " x " + std::to_string(s.height) + " px"; };
  if (m.values.type() != CV_32FC1 || m.valid.type() != CV_8UC1)
    throw InputError(which + " map: values must be CV_32FC1 with a CV_8UC1 validity mask, not " +
                     cv::typeToString(m.values.type()) + " and " + cv::typeToString(m.valid.type()));
  if (m.values.size() != size || m.valid.size() != size)
    throw InputError(which + " map is " + size_text(m.values.size()) + " (its validity mask " +
                     size_text(m.valid.size()) + "); the other map is " + size_text(size));
  if (!m.contact_mask.empty() && (m.contact_mask.type() != CV_8UC1 || m.contact_mask.size() != size))
    throw InputError(which + " map's contact mask is " + size_text(m.contact_mask.size()) + " " +
                     cv::typeToString(m.contact_mask.type()) + "; expected " + size_text(size) + " CV_8UC1");
}

}  // namespace

int ColourScale::index(double value) const {
  const double t = high > low ? (value - low) / (high - low) : 0.5;
  return static_cast<int>(std::lround(std::clamp(t, 0.0, 1.0) * 255));
}

cv::Vec3b ColourScale::colour(double value) const { return viridis().at<cv::Vec3b>(0, index(value)); }

ColourScale scale_of(const MapView& map, const std::string& unit) {
  if (map.values.empty() || cv::countNonZero(map.valid) == 0)
    throw InputError("'" + map.title + "' has no valid value to set the colour scale by");
  double low = 0, high = 0;
  cv::minMaxLoc(map.values, &low, &high, nullptr, nullptr, map.valid);
  if (!(high > low)) low -= 0.5, high += 0.5;
  return {low, high, unit};
}

cv::Point map_pixel_in_picture(cv::Size size, int which, int x, int y) {
  const int block = block_of(size);
  return {kMargin + which * (size.width * block + kGap) + x * block, kMargin + kTitle + y * block};
}

namespace {

// The maps side by side, titled, with the colour bar and the legend below;
// `outline` names what the contact outline shows.
cv::Mat draw_panels(const std::vector<const MapView*>& maps, const ColourScale& scale, const std::string& outline) {
  const cv::Size size = maps.back()->values.size();
  const int count = static_cast<int>(maps.size());
  const int block = block_of(size), w = size.width * block, h = size.height * block;
  const int width = 2 * kMargin + count * w + (count - 1) * kGap;
  const int legend_top = kMargin + kTitle + h + 10;
  cv::Mat picture(legend_top + kBar + 52, width, CV_8UC3, kPaper);

  bool outlined = false;
  for (int which = 0; which < count; ++which) {
    const MapView& m = *maps[static_cast<std::size_t>(which)];
    const cv::Point at = map_pixel_in_picture(size, which, 0, 0);
    put_text(picture, m.title, {at.x, kMargin + 14}, kTextColour);
    colour_map(m, scale, block).copyTo(picture(cv::Rect(at.x, at.y, w, h)));
    outlined = outlined || !m.contact_mask.empty();
  }

  // The colour bar: the scale from low (left) to high (right), labelled.
  const int bar_x = kMargin, bar_w = width - 2 * kMargin;
  for (int x = 0; x < bar_w; ++x) {
    const int i = static_cast<int>(std::lround(255.0 * x / std::max(1, bar_w - 1)));
    cv::line(picture, {bar_x + x, legend_top}, {bar_x + x, legend_top + kBar - 1},
             cv::Scalar(viridis().at<cv::Vec3b>(0, i)));
  }
  const int label_y = legend_top + kBar + 14;
  const std::string low = "<= " + number(scale.low, scale.unit), high = ">= " + number(scale.high, scale.unit);
  const std::string mid = number(0.5 * (scale.low + scale.high), scale.unit);
  put_text(picture, low, {bar_x, label_y}, kTextColour);
  const int mid_x = bar_x + (bar_w - text_width(mid)) / 2;
  if (mid_x > bar_x + text_width(low) + 8 && mid_x + text_width(mid) + 8 < bar_x + bar_w - text_width(high))
    put_text(picture, mid, {mid_x, label_y}, kTextColour);  // where it fits between the ends' labels
  put_text(picture, high, {bar_x + bar_w - text_width(high), label_y}, kTextColour);

  // The swatches: no value, contact outline.
  const int key_y = label_y + 20;
  int x = bar_x;
  const auto swatch = [&](const cv::Vec3b& colour, const std::string& text) {
    cv::rectangle(picture, cv::Rect(x, key_y - 10, 12, 12), cv::Scalar(colour), cv::FILLED);
    cv::rectangle(picture, cv::Rect(x, key_y - 10, 12, 12), kTextColour, 1);
    put_text(picture, text, {x + 17, key_y}, kTextColour);
    x += 17 + text_width(text) + 16;
  };
  swatch(kNoValue, "no value");
  if (outlined) swatch(kContactOutline, outline);
  return picture;
}

}  // namespace

cv::Mat draw_map_pair(const MapView& left, const MapView& right, const ColourScale& scale) {
  const cv::Size size = right.values.size();  // the truth's, in a pipeline's picture
  check(right, size, "'" + right.title + "'");
  check(left, size, "'" + left.title + "'");
  return draw_panels({&left, &right}, scale, "true contact region (outline)");
}

cv::Mat draw_map(const MapView& map, const ColourScale& scale) {
  check(map, map.values.size(), "'" + map.title + "'");
  return draw_panels({&map}, scale, "contact region (outline)");
}

}  // namespace touchcloud::imaging
