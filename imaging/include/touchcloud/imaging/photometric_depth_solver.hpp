// Classical depth from shading of a GelSight-type sensor: per pixel, the
// colour difference to the no-contact reference image through the
// photometric calibration's polynomial to a surface gradient, then the height
// by Poisson integration (DST, zero border). Pixels whose difference stays
// within `flat_grey` on every channel are taken as flat (gradient 0): the
// polynomial's value at a zero difference is not exactly zero, and noise
// would otherwise integrate to a drift. The contact mask is where the height
// exceeds `contact_height_mm` and the (smoothed) difference exceeds
// `contact_grey`.
//
// Pixels a caller excludes (a marker dot's ink: its colour is no shading)
// get no gradient of their own: each takes the mean gradient of the kept
// pixels around it (excluded_pixels.hpp).
//
// The border: `zero` (the usual assumption, the DST solver) takes the height
// as zero on the image's border, which holds while the contact stays inside
// the image; `free` (the DCT solver) assumes nothing there and fixes the
// constant by the flat pixels (no colour difference: no contact, height 0),
// so a contact that runs off the image keeps its height.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/imaging/dct_poisson.hpp"
#include "touchcloud/imaging/dst_poisson.hpp"
#include "touchcloud/imaging/excluded_pixels.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"

namespace touchcloud::imaging {

enum class PoissonBorder { Zero, Free };

struct DepthOptions {
  PoissonBorder border = PoissonBorder::Zero;
  double flat_grey = 3;
  double contact_height_mm = 0.05;
  double contact_grey = 6;
};

struct DepthResult {
  cv::Mat height_mm;     // CV_32FC1
  cv::Mat contact_mask;  // CV_8UC1
  cv::Mat gx, gy;        // CV_64FC1 pixel-centred gradients (dH/dx, dH/dy), for inspection: the solver's, until its next solve
  long flat_pixels = 0;  // pixels taken as flat (border free: the height's zero)
};

class PhotometricDepthSolver {
 public:
  PhotometricDepthSolver(sensor::PhotometricCalibration calibration, DepthOptions options);
  const sensor::PhotometricCalibration& calibration() const { return calibration_; }
  // image, reference: CV_8UC3 BGR of the calibration's size (checked by the caller).
  DepthResult solve(const cv::Mat& image, const cv::Mat& reference);
  // The same with the `excluded` pixels' gradients filled from around them.
  DepthResult solve(const cv::Mat& image, const cv::Mat& reference, const ExcludedPixels& excluded);

 private:
  sensor::PhotometricCalibration calibration_;
  DepthOptions options_;
  std::unique_ptr<DstPoisson> zero_border_;
  std::unique_ptr<DctPoisson> free_border_;
  void gradients(const cv::Mat& image, const cv::Mat& reference, DepthResult& out);
  DepthResult integrate(DepthResult out);
  std::vector<std::array<int, 3>> exponents_;  // the polynomial's terms: powers of r, g, b
  cv::Mat p_, q_;  // staggered gradients, reused
  cv::Mat gx_, gy_, difference_, height_;  // scratch of one frame, reused
  cv::Mat channel_difference_;
  std::vector<cv::Mat> channels_;
  ExcludedFill excluded_fill_;
};

}  // namespace touchcloud::imaging
