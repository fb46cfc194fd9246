// The marker dots of a GelSight-type gel masked and filled before the colour
// difference becomes a gradient: a dot's dark ink is no shading, and left in
// it would integrate to a bump. The dots are found by the marker detector
// (marker_detector.hpp) in the image and in the reference. The mask is each
// dot's ink: within a disc of the largest expected diameter plus a margin
// around each centre, the pixels darker than a grey closing of the image
// (the gel without its dots) by more than `ink_grey`, in either image, grown
// by one pixel for the dot's blurred rim. Only the ink: every pixel masked is
// shading lost, which matters most where a dot sits on a contact's rim. Both
// images are filled over that one mask by OpenCV's inpainting (Telea's fast
// marching: the fill follows the shading around the dot, at a cost that grows
// with the masked pixels only), which keeps their difference continuous where
// a dot was in one image and not in the other.
//
// The reference's dots are found once per reference image (the same pixels
// as last time: kept).
#pragma once

#include <cstddef>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/marker_detector.hpp"

namespace touchcloud::imaging {

struct MarkerFillOptions {
  MarkerDetectorOptions detector;  // dark dots, the sensor's dot size and contrast
  double margin_px = 1.5;          // added to the largest dot's radius
  double inpaint_radius_px = 3;    // the neighbourhood each filled pixel is taken from
  double ink_grey = 4;             // darker than the gel around it by more than this: a dot's pixel
};

struct FilledPair {
  cv::Mat image, reference;        // CV_8UC3, filled (views of scratch kept by the filler: valid until its next call)
  cv::Mat mask;                    // CV_8UC1, 255 where filled
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

  MarkerFillOptions options_;
  MarkerDetector detector_;
  cv::Mat reference_seen_;     // a copy of the reference whose dots are kept
  std::vector<Marker> reference_dots_;
  cv::Mat window_;  // the closing's structuring element (the detector's background window)
  cv::Mat grey_, closed_, discs_, ink_image_, ink_reference_, mask_, image_out_, reference_out_;
};

}  // namespace touchcloud::imaging
