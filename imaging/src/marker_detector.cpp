#include "touchcloud/imaging/marker_detector.hpp"
#include "touchcloud/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "dot_window.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::imaging {

namespace {


constexpr double kDiscFill = M_PI / 4;  // a disc's share of its bounding box
// Blur and anti-aliasing widen a thresholded dot by about a pixel each side,
// and a faint dot's thresholded core is narrower than the dot.
constexpr int kExtentSlackBelowPx = 1, kExtentSlackAbovePx = 2;
// Pixels between a blob's bounding box and its window's rim: the blurred rim
// of a dot fades to the background within about this distance.
constexpr int kWindowMarginPx = 3;
// Centroid weights start this share of the contrast threshold above the
// window rim's level (see dot_window.hpp): noise well below the threshold
// then weighs nothing. On rendered frames with 2 grey levels of noise, half
// the threshold (15 grey levels) gave centres 3x closer than no floor.
constexpr double kWeightFloorOfThreshold = 0.5;
// Dots that touch or overlap in the image (oblique views near the gel's rim)
// form one blob; up to this many are split apart.
constexpr int kMaxDotsInClump = 6;
// A dot's ink relative to its width (DotMoments::dots_by_ink) is below 1 and
// depends on blur; the image's own round, compact blobs calibrate it.
constexpr double kRoundElongation = 1.25;
constexpr double kDefaultSingleDotInk = 0.85;
// A cut dot's completeness when the image has no whole round dot to compare.
constexpr double kUnknownCompleteness = 0.5;

struct Blob {
  cv::Rect box;
  int area;
  bool cut;          // touches the image border: a dot cut by it
  DotWindow window;  // box and margin, inside the image
  DotMoments moments;
  int extent() const { return std::max(box.width, box.height); }
  double fill() const { return static_cast<double>(area) / box.area(); }
};

bool touches_border(const cv::Rect& box, cv::Size image) {
  return box.x == 0 || box.y == 0 || box.x + box.width == image.width || box.y + box.height == image.height;
}

double median(std::vector<double> values, double fallback) {
  if (values.empty()) return fallback;
  auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace

void MarkerDetectorOptions::check() const {
  if (!(min_diameter_px > 0)) throw ParameterError("diameter_px", "the smallest diameter must be > 0 px");
  if (!(max_diameter_px >= min_diameter_px))
    throw ParameterError("diameter_px", "[min, max] must have min <= max, got [" + number_text(min_diameter_px) +
                                            ", " + number_text(max_diameter_px) + "]");
  if (max_diameter_px > 200) throw ParameterError("diameter_px", "the largest diameter must be <= 200 px");
  if (!(contrast_grey > 0 && contrast_grey < 255)) throw ParameterError("contrast_grey", "must be in (0, 255)");
  if (background_window_px != 0 && background_window_px <= max_diameter_px)
    throw ParameterError("background_window_px", number_text(background_window_px) +
                                                     " px must be wider than the largest dot (" +
                                                     number_text(max_diameter_px) + " px), or 0 for automatic");
  if (!(min_fill >= 0 && min_fill <= 1)) throw ParameterError("min_fill", "must be in [0, 1]");
  if (!(max_elongation >= 1)) throw ParameterError("max_elongation", "must be >= 1");
  if (!(min_quality >= 0 && min_quality <= 1)) throw ParameterError("min_quality", "must be in [0, 1]");
}

int MarkerDetectorOptions::background_window() const {
  const int w = background_window_px > 0 ? background_window_px : static_cast<int>(std::ceil(max_diameter_px)) + 3;
  return w | 1;
}

std::string image_type_name(const cv::Mat& image) { return cv::typeToString(image.type()); }

MarkerDetector::MarkerDetector(MarkerDetectorOptions options)
    : options_((options.check(), options)),
      background_(options_.polarity == MarkerPolarity::Dark, options_.background_window()) {}

std::vector<Marker> MarkerDetector::detect(const cv::Mat& image, const std::string& what) {
  if (image.empty()) throw InputError(what + " is empty");
  const cv::Mat* grey = &image;
  if (image.type() == CV_8UC3) {
    cv::cvtColor(image, grey_, cv::COLOR_BGR2GRAY);
    grey = &grey_;
  } else if (image.type() != CV_8UC1) {
    throw InputError(what + " is " + image_type_name(image) +
                     "; the marker detector takes 8-bit grey (CV_8UC1) or BGR (CV_8UC3) images");
  }

  background_.estimate(*grey);
  const int threshold = static_cast<int>(std::floor(options_.contrast_grey));
  blobs_.find(grey->rows, grey->cols, [&](int y, MaskBlobs::RowBits& bits) {
    background_.mask_row(*grey, y, threshold, bits);
  });
  return measure_blobs(*grey);
}

std::vector<Marker> MarkerDetector::measure_blobs(const cv::Mat& grey) const {
  // Every blob that could be a dot or a clump of a few, measured.
  const double min_extent = options_.min_diameter_px - kExtentSlackBelowPx;
  const double max_extent = options_.max_diameter_px + kExtentSlackAbovePx;
  const double max_area = kDiscFill * max_extent * max_extent;
  const cv::Size size = grey.size();
  const bool dark = options_.polarity == MarkerPolarity::Dark;
  const ContrastLevels levels{static_cast<int>(std::floor(options_.contrast_grey)),
                                      kWeightFloorOfThreshold * options_.contrast_grey};
  std::vector<Blob> candidates;
  candidates.reserve(blobs_.blobs().size());
  std::vector<double> single_ink, single_area;
  // A dot's ink over its contrast above the weight floor: about its area in
  // px, whatever the lighting.
  auto ink_area = [&](const DotMoments& m) { return m.ink / std::max(1.0, m.peak_grey - levels.weight_floor_grey); };
  for (const MaskBlob& mb : blobs_.blobs()) {
    Blob b{mb.box, mb.area, touches_border(mb.box, size), {}, {}};
    if (b.extent() < min_extent || b.extent() > 3 * max_extent || b.area > kMaxDotsInClump * max_area) continue;
    if (b.cut && options_.border == BorderDots::Drop) continue;
    constexpr int m = kWindowMarginPx;
    b.window = fit_window(cv::Rect(b.box.x - m, b.box.y - m, b.box.width + 2 * m, b.box.height + 2 * m), size);
    b.moments = measure_dot(grey, dark, b.window, b.box, levels);
    if (!(b.moments.ink > 0)) continue;
    if (b.extent() <= max_extent && b.moments.elongation() <= kRoundElongation && !b.moments.clipped) {
      single_ink.push_back(b.moments.dots_by_ink());
      single_area.push_back(ink_area(b.moments));
    }
    candidates.push_back(b);
  }
  const double ink_per_dot = std::clamp(median(single_ink, kDefaultSingleDotInk), 0.4, 1.2);
  const double whole_dot_area = median(single_area, 0.0);  // 0: no whole dot to compare with

  std::vector<Marker> markers;
  markers.reserve(candidates.size());
  auto quality = [&](const DotMoments& m, double shape, double completeness) {
    // marker_detector.hpp defines it.
    return std::min(1.0, m.peak_grey / (4 * options_.contrast_grey)) * std::clamp(shape, 0.0, 1.0) *
           std::clamp(completeness, 0.0, 1.0);
  };
  // A cut dot's share of a whole one; without a whole dot to compare, half.
  auto completeness = [&](const DotMoments& m) {
    return whole_dot_area > 0 ? ink_area(m) / whole_dot_area : kUnknownCompleteness;
  };
  auto keep = [&](const Eigen::Vector2d& centre, double q) {
    if (q >= options_.min_quality) markers.push_back({centre, -1, q});
  };
  auto inside_box = [](const Eigen::Vector2d& p, const cv::Rect& box) {
    return p.x() >= box.x - 1 && p.x() <= box.x + box.width && p.y() >= box.y - 1 && p.y() <= box.y + box.height;
  };
  for (const Blob& b : candidates) {
    if (b.cut) {
      // One marker at most: the ink of a cut dot is narrow across the cut,
      // which would read as several dots; its shape is the cut's, not the dot's.
      if (b.extent() > max_extent || b.area > max_area || b.fill() < options_.min_fill) continue;
      if (!inside_box(b.moments.centre_px, b.box)) continue;
      keep(b.moments.centre_px, quality(b.moments, b.fill() / kDiscFill, completeness(b.moments)));
      continue;
    }
    const long dots = std::max(1l, std::lround(b.moments.dots_by_ink() / ink_per_dot));
    if (dots == 1) {
      if (b.extent() > max_extent || b.area > max_area || b.fill() < options_.min_fill ||
          b.moments.elongation() > options_.max_elongation)
        continue;
      const DotMoments& m = b.moments;
      if (!inside_box(m.centre_px, b.box)) continue;
      keep(m.centre_px, quality(m, b.fill() / kDiscFill, 1.0));
    } else if (dots <= kMaxDotsInClump) {
      const int n = static_cast<int>(dots);
      for (const DotMoments& m : split_clump(grey, dark, b.window, b.box, levels, b.moments, n)) {
        if (!(m.ink > 0) || m.elongation() > options_.max_elongation || !inside_box(m.centre_px, b.box)) continue;
        keep(m.centre_px, 0.5 * quality(m, 1.0, 1.0));  // a share of a clump: less sure
      }
    }
  }
  return markers;
}

}  // namespace touchcloud::imaging
