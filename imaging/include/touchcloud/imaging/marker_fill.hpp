// The marker dots of a GelSight-type gel masked and filled before the colour
// difference becomes a gradient: a dot's dark ink is no shading, and left in
// it would integrate to a bump. The dots are found by the marker detector
// (marker_detector.hpp) in the image and in the reference. The mask is each
// dot's ink: within a disc of the largest expected diameter plus a margin
// around each centre, the pixels darker than a grey closing of the image
// (square window, the detector's background window: the gel without its
// dots) by more than `ink_grey`, grown by one pixel for the dot's blurred
// rim. Only the ink: every pixel masked is shading lost, which matters most
// where a dot sits on a contact's rim. Each image is filled over its own
// mask, so each becomes an estimate of the gel without dots: per dot and
// channel, a quadratic in x and y fitted by least squares to the unmasked
// pixels of a ring `ring_px` wide around the dot's disc gives the masked
// pixels. The shading around a dot is smooth (the lights' response to the
// gel's normals), so a quadratic follows it; and it is fast: OpenCV's
// inpainting (Telea) took 83 us for one 23 x 23 window on one core, so 60-120
// dots a frame would eat the 5 ms a frame has at 200 frames/s.
//
// The reference's dots and its fill are made once per reference image (the
// same pixels as last time: kept).
#pragma once

#include <cstddef>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/marker_detector.hpp"

namespace touchcloud::imaging {

struct MarkerFillOptions {
  MarkerDetectorOptions detector;  // dark dots, the sensor's dot size and contrast
  double margin_px = 1.5;          // added to the largest dot's radius
  double ring_px = 3;              // width of the ring around each dot's disc that the fill is fitted to
  double ink_grey = 4;             // darker than the gel around it by more than this: a dot's pixel
};

struct FilledPair {
  cv::Mat image, reference;        // CV_8UC3, filled (views of scratch kept by the filler: valid until its next call)
  cv::Mat mask;                    // CV_8UC1, 255 where either was filled
  std::size_t image_markers = 0;   // dots found in the image
  std::size_t reference_markers = 0;
};

class MarkerFill {
 public:
  explicit MarkerFill(MarkerFillOptions options);  // ParameterError for bad detector options
  const MarkerFillOptions& options() const { return options_; }

  // image, reference: CV_8UC3 BGR of one size.
  FilledPair fill(const cv::Mat& image, const cv::Mat& reference);

 private:
  void add_discs(const std::vector<Marker>& markers, cv::Mat& mask) const;
  void ink(const cv::Mat& bgr, cv::Mat& out);  // 255 where darker than the closing by more than ink_grey
  void dot_mask(const cv::Mat& bgr, const std::vector<Marker>& dots, cv::Mat& mask);  // the dots' ink
  void fill_dots(const cv::Mat& bgr, const std::vector<Marker>& dots, const cv::Mat& mask, cv::Mat& out);
  double disc_radius() const { return 0.5 * options_.detector.max_diameter_px + options_.margin_px; }

  MarkerFillOptions options_;
  MarkerDetector detector_;
  cv::Mat reference_seen_;     // a copy of the reference whose dots are kept
  std::vector<Marker> reference_dots_;
  cv::Mat window_;  // the closing's structuring element (the detector's background window)
  cv::Mat reference_mask_, reference_out_;  // of the kept reference
  cv::Mat grey_, closed_, discs_, mask_, union_, image_out_, own_, patch_;
};

}  // namespace touchcloud::imaging
