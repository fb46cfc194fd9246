// Height from gradients by Poisson integration with a zero boundary: the
// discrete Poisson equation (5-point Laplacian) on the image's interior,
// solved exactly by a 2-D type-I discrete sine transform (FFTW's RODFT00),
// which diagonalises the Laplacian with zero Dirichlet boundary. The plan is
// made once per image size (FFTW_ESTIMATE: the same plan, hence the same
// bits, on every run) and reused for every frame.
//
// Gradients are staggered forward differences in height units per pixel:
// p(u, v) = H(u + 1, v) - H(u, v) (width - 1 columns), q(u, v) = H(u, v + 1) -
// H(u, v) (height - 1 rows); for exactly such gradients of an H that is zero
// on the border the solution is H again, to rounding.
#pragma once

#include <opencv2/core.hpp>

namespace touchcloud::photometric {

class DstPoisson {
 public:
  DstPoisson(int width_px, int height_px);  // at least 3 x 3
  ~DstPoisson();
  DstPoisson(const DstPoisson&) = delete;
  DstPoisson& operator=(const DstPoisson&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  // p: CV_64FC1 of height x (width - 1); q: CV_64FC1 of (height - 1) x width.
  // Returns CV_64FC1 height x width, zero on the border.
  cv::Mat solve(const cv::Mat& p, const cv::Mat& q);

 private:
  int width_, height_, nx_, ny_;
  double* buffer_ = nullptr;  // ny x nx, row-major
  void* plan_ = nullptr;      // fftw_plan
  cv::Mat eigen_;             // ny x nx: the Laplacian's eigenvalues times the transforms' scale
};

}  // namespace touchcloud::photometric
