// Height from gradients by Poisson integration with a zero boundary: the
// discrete Poisson equation (5-point Laplacian) on the image's interior,
// solved exactly. A type-I discrete sine transform along the rows
// diagonalises the row direction's second difference with zero ends and
// leaves, for each row frequency, a tridiagonal system down the column,
// solved directly (Thomas; strictly diagonally dominant). The plan is made
// once per image size (FFTW_ESTIMATE: the same plan, hence the same bits, on
// every run) and reused for every frame.
//
// Speed: a sine transform of n points costs what a complex DFT of 2 (n + 1)
// points does, and n + 1 is the image's width less one: 319 = 11 x 29 at 320
// px, where FFTW's real-to-real transforms fall back to slow generic code.
// So the rows are transformed as complex DFTs (two rows in one, their
// odd extensions as real and imaginary parts; FFTW's vectorised codelets),
// and the interior is widened by a few columns, to the next width whose
// n + 1 has only the factors 2, 3, 5 and 7 (320 at 320 px). Those columns
// are held at zero height by a source on them chosen to cancel them (the
// capacitance matrix method: one small dense system per column frequency,
// prepared once), so the solution on the image is the zero-border one, to
// rounding. Not a 2-D sine transform: 240 rows have 238 interior ones, 239
// prime.
//
// Gradients are staggered forward differences in height units per pixel:
// p(u, v) = H(u + 1, v) - H(u, v) (width - 1 columns), q(u, v) = H(u, v + 1) -
// H(u, v) (height - 1 rows); for exactly such gradients of an H that is zero
// on the border the solution is H again, to rounding.
#pragma once

#include <vector>

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
  // The same into `height` (made CV_64FC1 height x width if it is not).
  void solve(const cv::Mat& p, const cv::Mat& q, cv::Mat& height);

 private:
  template <class Row>
  void transform(Row&& row);  // the sine transform of each row, two at a time
  template <class Out>
  void transformed_rows(int columns, Out&& out) const;  // its result, row by row
  void solve_columns(cv::Mat& spectrum) const;                 // Thomas down every column at once
  void cancel_extra_columns();                                 // the capacitance correction on spectrum_

  int width_, height_, nx_, ny_;
  int columns_;             // interior columns transformed: nx_ and the extra ones, columns_ + 1 with factors 2, 3, 5, 7
  int period_;              // 2 (columns_ + 1): the complex DFT's length
  void* wave_ = nullptr;    // fftw_complex[(ny_ + 1) / 2][period_]: two rows' odd extensions
  void* transformed_ = nullptr;  // the same shape: their DFTs
  void* plan_ = nullptr;    // fftw_plan: every pair of rows' DFT
  cv::Mat spectrum_;  // ny_ x columns_: the transformed divergence, then the transformed height
  std::vector<double> row_pair_[2];  // two rows on their way into the transform
  // Thomas' elimination for each row frequency k, fixed by the size: the
  // reciprocal pivots, which are also the eliminated super-diagonal (ny x
  // columns_).
  cv::Mat inverse_pivot_;
  // The extra columns' capacitance: each one's sine (extra x columns_), the
  // column direction's sine modes scaled to be their own inverse (ny x ny),
  // and per column mode the inverse of the extra columns' response (ny x
  // extra^2); scratch for the heights there and the cancelling source.
  cv::Mat extra_sine_, column_modes_, response_inverse_, extra_height_, source_, correction_;
};

}  // namespace touchcloud::imaging
