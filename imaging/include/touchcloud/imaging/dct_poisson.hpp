// Height from gradients by Poisson integration with a free border: the
// discrete Poisson equation with zero flux through the image's border (the
// Neumann problem of the staggered gradients), solved exactly by a 2-D
// type-II/III discrete cosine transform (FFTW's REDFT10 and REDFT01). Unlike
// the zero-border solver (dst_poisson.hpp) it assumes nothing about the
// height at the border, so a contact that runs off the image keeps its
// shape; the height is then known up to a constant, which the caller fixes
// (photometric_depth: zero on the pixels without contact). Planned once per
// image size (FFTW_ESTIMATE).
//
// For exact staggered gradients (dst_poisson.hpp's convention) of any height
// map H, the solution is H minus its mean, to rounding.
#pragma once

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

class DctPoisson {
 public:
  DctPoisson(int width_px, int height_px);  // at least 2 x 2
  ~DctPoisson();
  DctPoisson(const DctPoisson&) = delete;
  DctPoisson& operator=(const DctPoisson&) = delete;

  // p: CV_64FC1 of height x (width - 1); q: CV_64FC1 of (height - 1) x width.
  // Returns CV_64FC1 height x width with mean zero.
  cv::Mat solve(const cv::Mat& p, const cv::Mat& q);

 private:
  int width_, height_;
  double* buffer_ = nullptr;
  void* forward_ = nullptr;  // fftw_plan, DCT-II
  void* inverse_ = nullptr;  // fftw_plan, DCT-III
  cv::Mat eigen_;
};

}  // namespace touchcloud::imaging
