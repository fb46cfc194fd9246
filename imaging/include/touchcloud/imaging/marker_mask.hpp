// The marker dots of a GelSight-type gel found and masked before the colour
// difference becomes a gradient: a dot's dark ink is no shading, and read as
// shading it would integrate to a bump. The dots are found by the marker
// detector (marker_detector.hpp) in the image and in the reference. The mask
// is each dot's ink: within a disc of the largest expected diameter plus a
// margin around each centre, the pixels darker than a grey closing of the
// image (square window, the detector's background window: the gel without
// its dots) by more than `ink_grey`, grown by one pixel for the dot's
// blurred rim; a dot found in the reference but lost in the image is
// looked for near its rest place (add_lost_dots). Only the ink: every pixel masked is shading lost, which
// matters most where a dot sits on a contact's rim. The depth and the
// calibration read no colour there (excluded_pixels.hpp): no colour is
// guessed across a dot, which on a contact's rim gives a slope neither
// side has.
//
// The reference's dots and mask are made once per reference image (the
// same pixels as last time: kept).
#pragma once

#include <cstddef>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/excluded_pixels.hpp"
#include "touchcloud/imaging/marker_detector.hpp"

namespace touchcloud::imaging {

struct MarkerMaskOptions {
  MarkerDetectorOptions detector;  // dark dots, the sensor's dot size and contrast
  double margin_px = 1.5;          // added to the largest dot's radius
  double ink_grey = 4;             // darker than the gel around it by more than this: a dot's pixel
};

struct MarkerMasks {
  ExcludedPixels excluded;         // 255 on a dot's ink in either image (scratch: valid until the next call)
  std::size_t image_markers = 0;   // dots found in the image
  std::size_t reference_markers = 0;
};

class MarkerMask {
 public:
  explicit MarkerMask(MarkerMaskOptions options);  // ParameterError for bad detector options
  const MarkerMaskOptions& options() const { return options_; }

  // image, reference: CV_8UC3 BGR of one size.
  MarkerMasks masks(const cv::Mat& image, const cv::Mat& reference);

 private:
  void add_discs(const std::vector<Marker>& markers, double radius, cv::Mat& mask) const;
  void ink(const cv::Mat& bgr, cv::Mat& out);  // 255 where darker than the closing by more than ink_grey
  void dot_mask(const cv::Mat& bgr, const std::vector<Marker>& dots, cv::Mat& mask);  // the dots' ink
  // A dot of the reference with none of the image's within the largest dot's
  // diameter (a pressed dot moves less): the detector lost it, as where the
  // press shades the gel around it dark and the dot's blob merges with the
  // shade. Its ink left in would integrate to a bump: within that reach of
  // its rest place, the pixels darker in every channel than the colour
  // closing are added to `mask`.
  void add_lost_dots(const cv::Mat& image, const std::vector<Marker>& dots, cv::Mat& mask);
  double disc_radius() const { return 0.5 * options_.detector.max_diameter_px + options_.margin_px; }

  MarkerMaskOptions options_;
  MarkerDetector detector_;
  cv::Mat reference_seen_;     // a copy of the reference whose dots are kept
  std::vector<Marker> reference_dots_;
  std::vector<Marker> lost_;  // scratch
  cv::Mat closed_colour_, lost_ink_;
  cv::Mat window_;  // the closing's structuring element (the detector's background window)
  cv::Mat reference_mask_;  // of the kept reference
  cv::Mat grey_, closed_, discs_, mask_, union_;
};

}  // namespace touchcloud::imaging
