// Finds the round marker dots of the gel in one 8-bit image, with sub-pixel
// centres. The method, chosen to stay within a few milliseconds per 1280 x 720
// image on one core:
//
//   background  morphological closing (dark dots) or opening (bright dots)
//               with a window wider than the largest dot, then a box blur,
//               on a copy shrunk 2-4x (dot_background.hpp): follows
//               vignetting and lighting gradients, ignores the dots
//   contrast    |background - image| past `contrast_grey` marks dot pixels
//   blobs       8-connected components (mask_blobs.hpp), kept when their size, fill and
//               elongation fit a dot of the expected diameter; a blob whose
//               ink amounts to several dots (dots that touch in the image)
//               is split by weighted k-means
//   centre      contrast-weighted centroid over a window around the blob,
//               the window's rim giving the local zero of contrast
//   border      a blob that touches the image border is a dot cut by it:
//               one marker (never split, its centre the centroid of what is
//               visible) or none, as `border` says
//
// Quality, in [0, 1], is the product of three shares:
//   contrast      min(1, peak contrast / (4 x contrast_grey)): 1 for a dot
//                 that stands four thresholds clear of its background
//   shape         min(1, blob fill / a disc's fill (pi / 4)): 1 for a dot
//                 that fills its bounding box as a disc does
//   completeness  1 for a dot wholly inside the image; for one cut by the
//                 border, its ink over that of a whole dot (the median of the
//                 image's round dots), at most 1
// and halved for each dot of a split clump (its share of the ink is less
// sure). `min_quality` drops markers below it.
//
// A detector reuses its scratch images between calls: use one per thread.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/dot_background.hpp"
#include "touchcloud/imaging/mask_blobs.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::imaging {

enum class MarkerPolarity { Dark, Bright };  // dots darker or brighter than the gel around them
enum class BorderDots { Keep, Drop };         // a dot cut by the image border: one marker, or none

struct MarkerDetectorOptions {
  MarkerPolarity polarity = MarkerPolarity::Dark;
  double min_diameter_px = 3.0;   // expected dot diameter range in the image
  double max_diameter_px = 12.0;
  double contrast_grey = 30.0;    // least dot-to-background difference that counts as a dot pixel
  int background_window_px = 0;   // closing/opening window; 0: max_diameter_px + 3, made odd
  double min_fill = 0.5;          // blob area / bounding-box area (a disc fills 0.785)
  double max_elongation = 2.0;    // longest / shortest principal axis of a dot's contrast (a disc: 1)
  BorderDots border = BorderDots::Keep;
  double min_quality = 0.0;       // markers of lower quality (see above) are dropped

  // Throws ParameterError naming the option when a value breaks its rule.
  void check() const;
  int background_window() const;  // the window used, in px (odd)
};

class MarkerDetector {
 public:
  explicit MarkerDetector(MarkerDetectorOptions options);
  const MarkerDetectorOptions& options() const { return options_; }

  // Markers in `image` (CV_8UC1 grey, or CV_8UC3 BGR converted to grey), in
  // row-major order of their blobs; id -1. Throws InputError naming `what`
  // ("image" unless told) when the image is empty or of another type.
  std::vector<Marker> detect(const cv::Mat& image, const std::string& what = "image");

 private:
  std::vector<Marker> measure_blobs(const cv::Mat& grey) const;  // of the blobs found

  MarkerDetectorOptions options_;
  DotBackground background_;
  MaskBlobs blobs_;
  cv::Mat grey_;  // a BGR image converted, kept between calls
};

// The image's OpenCV type as text ("CV_16UC1"), for error messages.
std::string image_type_name(const cv::Mat& image);

}  // namespace touchcloud::imaging
