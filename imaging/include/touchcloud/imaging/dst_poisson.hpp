// Height from gradients by Poisson integration with a zero boundary: the
// discrete Poisson equation (5-point Laplacian) on the image's interior,
// solved exactly. A type-I discrete sine transform along the rows (FFTW's
// RODFT00, which diagonalises the row direction's second difference with
// zero ends) leaves, for each row frequency, a tridiagonal system down the
// column, solved directly (Thomas; strictly diagonally dominant). Not a 2-D
// sine transform: at 240 rows the interior's 238 make FFTW work on 2 x 239
// points, 239 prime, four times slower than the whole rest. The plan is
// made once per image size (FFTW_ESTIMATE: the same plan, hence the same
// bits, on every run) and reused for every frame.
//
// Gradients are staggered forward differences in height units per pixel:
// p(u, v) = H(u + 1, v) - H(u, v) (width - 1 columns), q(u, v) = H(u, v + 1) -
// H(u, v) (height - 1 rows); for exactly such gradients of an H that is zero
// on the border the solution is H again, to rounding.
#pragma once

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

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
  void* plan_ = nullptr;      // fftw_plan: every row's sine transform
  // Thomas' elimination for each row frequency k, fixed by the size: the
  // reciprocal pivots and the eliminated super-diagonal (ny x nx each).
  cv::Mat inverse_pivot_, upper_;
};

}  // namespace touchcloud::imaging
