#include "touchcloud/imaging/dst_poisson.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <fftw3.h>

#include "fftw_planner.hpp"

namespace touchcloud::imaging {

namespace {

// n has no prime factor above 7: FFTW's codelets cover it.
bool smooth(int n) {
  for (int f : {2, 3, 5, 7})
    while (n % f == 0) n /= f;
  return n == 1;
}

}  // namespace

DstPoisson::DstPoisson(int width_px, int height_px)
    : width_(width_px), height_(height_px), nx_(width_px - 2), ny_(height_px - 2) {
  if (nx_ < 1 || ny_ < 1)
    throw std::invalid_argument("Poisson integration needs at least 3 x 3 pixels, not " + std::to_string(width_px) +
                                " x " + std::to_string(height_px));
  columns_ = nx_;
  while (!smooth(columns_ + 1)) ++columns_;
  period_ = 2 * (columns_ + 1);
  const int pairs = (ny_ + 1) / 2;
  wave_ = fftw_malloc(sizeof(fftw_complex) * pairs * period_);
  transformed_ = fftw_malloc(sizeof(fftw_complex) * pairs * period_);
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    auto* wave = static_cast<fftw_complex*>(wave_);
    auto* transformed = static_cast<fftw_complex*>(transformed_);
    // Out of place: FFTW's in-place plan copies each row through a buffer.
    plan_ = fftw_plan_many_dft(1, &period_, pairs, wave, nullptr, 1, period_, transformed, nullptr, 1, period_,
                               FFTW_FORWARD, FFTW_ESTIMATE);
  }
  if (!plan_) {
    fftw_free(wave_);
    fftw_free(transformed_);
    throw std::runtime_error("FFTW could not plan " + std::to_string(pairs) + " DFTs of " + std::to_string(period_) +
                             " points");
  }
  spectrum_.create(ny_, columns_, CV_64FC1);
  // Row frequency k turns the 5-point Laplacian into H(l - 1) + d_k H(l) +
  // H(l + 1) down the column, d_k = 2 cos(pi (k + 1) / (columns + 1)) - 4,
  // with H = 0 above the first and below the last interior row.
  auto row_eigenvalue = [&](int k) { return 2 * std::cos(M_PI * (k + 1) / (columns_ + 1)) - 2; };
  // With ones beside the diagonal, the eliminated super-diagonal is the
  // reciprocal pivot itself: one table serves both sweeps.
  inverse_pivot_.create(ny_, columns_, CV_64FC1);
  for (int k = 0; k < columns_; ++k) {
    const double d = row_eigenvalue(k) - 2;
    double inverse = 0;
    for (int l = 0; l < ny_; ++l) {
      const double pivot = d - inverse;  // |d| > 2 keeps every pivot below -1
      inverse = 1 / pivot;
      inverse_pivot_.at<double>(l, k) = inverse;
    }
  }
  const int extra = columns_ - nx_;
  if (extra == 0) return;
  // A source s_a on extra column a adds 2 sin_a(k) s_a to row frequency k;
  // the heights on column b are (1 / (columns + 1)) sum_k sin_b(k) H_k. Down
  // the columns, every T_k is diagonal in the sine modes (eigenvalue
  // row_eigenvalue(k) + column_eigenvalue(j)), so the response of the extra
  // columns' heights to their sources is one extra x extra matrix per
  // column mode j.
  extra_sine_.create(extra, columns_, CV_64FC1);
  for (int a = 0; a < extra; ++a)
    for (int k = 0; k < columns_; ++k)
      extra_sine_.at<double>(a, k) = std::sin(M_PI * (k + 1) * (nx_ + 1 + a) / (columns_ + 1));
  column_modes_.create(ny_, ny_, CV_64FC1);
  const double norm = std::sqrt(2.0 / (ny_ + 1));
  for (int j = 0; j < ny_; ++j)
    for (int l = 0; l < ny_; ++l) column_modes_.at<double>(j, l) = norm * std::sin(M_PI * (j + 1) * (l + 1) / (ny_ + 1));
  response_inverse_.create(ny_, extra * extra, CV_64FC1);
  for (int j = 0; j < ny_; ++j) {
    const double column_eigenvalue = 2 * std::cos(M_PI * (j + 1) / (ny_ + 1)) - 2;
    Eigen::MatrixXd response = Eigen::MatrixXd::Zero(extra, extra);
    for (int k = 0; k < columns_; ++k) {
      const double weight = 2.0 / (columns_ + 1) / (row_eigenvalue(k) + column_eigenvalue);
      for (int a = 0; a < extra; ++a)
        for (int b = 0; b < extra; ++b)
          response(a, b) += weight * extra_sine_.at<double>(a, k) * extra_sine_.at<double>(b, k);
    }
    const Eigen::MatrixXd inverse = response.inverse();  // negative definite: every eigenvalue sum is below 0
    for (int a = 0; a < extra; ++a)
      for (int b = 0; b < extra; ++b) response_inverse_.at<double>(j, a * extra + b) = inverse(a, b);
  }
  extra_height_.create(extra, ny_, CV_64FC1);
  source_.create(extra, ny_, CV_64FC1);
  correction_.create(ny_, columns_, CV_64FC1);
}

DstPoisson::~DstPoisson() {
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_destroy_plan(static_cast<fftw_plan>(plan_));
  fftw_free(wave_);
  fftw_free(transformed_);
}

// Rows 2i and 2i + 1, oddly extended to period_ points, as the real and
// imaginary parts of one complex row: its DFT at k + 1 is -i S_2i(k) +
// S_2i+1(k), with S FFTW's RODFT00 (2 sum_j x_j sin(pi (j + 1) (k + 1) /
// (columns + 1))). `row(l, values)` writes row l's columns_ values.
template <class Row>
void DstPoisson::transform(Row&& row) {
  auto* wave = static_cast<fftw_complex*>(wave_);
  const int pairs = (ny_ + 1) / 2;
  std::vector<double>& a = row_pair_[0];
  std::vector<double>& b = row_pair_[1];
  a.resize(static_cast<std::size_t>(columns_));
  b.resize(static_cast<std::size_t>(columns_));
  for (int i = 0; i < pairs; ++i) {
    double* z = wave[static_cast<std::size_t>(i) * period_];
    row(2 * i, a.data());
    if (2 * i + 1 < ny_) row(2 * i + 1, b.data());
    else std::fill(b.begin(), b.end(), 0.0);
    double* mirror = z + 2 * static_cast<std::size_t>(period_ - 1);  // z[period - 1 - k]
    z[0] = z[1] = 0;
    z[2 * (columns_ + 1)] = z[2 * (columns_ + 1) + 1] = 0;
    for (int k = 0; k < columns_; ++k, mirror -= 2) {
      const double re = a[k], im = b[k];
      z[2 * k + 2] = re;
      z[2 * k + 3] = im;
      mirror[0] = -re;
      mirror[1] = -im;
    }
  }
  fftw_execute(static_cast<fftw_plan>(plan_));
}

// The transform of row l at column k, written by `out(l, k, value)`.
template <class Out>
void DstPoisson::transformed_rows(int columns, Out&& out) const {
  const auto* transformed = static_cast<const fftw_complex*>(transformed_);
  const int pairs = (ny_ + 1) / 2;
  for (int i = 0; i < pairs; ++i) {
    const fftw_complex* z = transformed + static_cast<std::size_t>(i) * period_;
    for (int k = 0; k < columns; ++k) out(2 * i, k, -z[k + 1][1]);
    if (2 * i + 1 == ny_) continue;
    for (int k = 0; k < columns; ++k) out(2 * i + 1, k, z[k + 1][0]);
  }
}

// Down every column at once, row by row: forward elimination, then back
// substitution.
void DstPoisson::solve_columns(cv::Mat& spectrum) const {
  const std::size_t n = static_cast<std::size_t>(columns_);
  {
    double* row = spectrum.ptr<double>(0);
    const double* inverse_pivot = inverse_pivot_.ptr<double>(0);
    for (std::size_t k = 0; k < n; ++k) row[k] *= inverse_pivot[k];
  }
  for (int l = 1; l < ny_; ++l) {
    double* __restrict row = spectrum.ptr<double>(l);
    const double* __restrict above = spectrum.ptr<double>(l - 1);
    const double* __restrict inverse_pivot = inverse_pivot_.ptr<double>(l);
    for (std::size_t k = 0; k < n; ++k) row[k] = (row[k] - above[k]) * inverse_pivot[k];
  }
  for (int l = ny_ - 2; l >= 0; --l) {
    double* __restrict row = spectrum.ptr<double>(l);
    const double* __restrict below = spectrum.ptr<double>(l + 1);
    const double* __restrict upper = inverse_pivot_.ptr<double>(l);
    for (std::size_t k = 0; k < n; ++k) row[k] -= upper[k] * below[k];
  }
}

// The heights the extra columns got, cancelled by the sources on them that
// give minus those heights there: s = -C^-1 h, C^-1 applied in the column
// modes; their own solution added to the spectrum.
void DstPoisson::cancel_extra_columns() {
  const int extra = columns_ - nx_;
  const double per_column = 1.0 / (columns_ + 1);
  for (int a = 0; a < extra; ++a) {
    const double* sine = extra_sine_.ptr<double>(a);
    double* height = extra_height_.ptr<double>(a);
    for (int l = 0; l < ny_; ++l) {
      const double* row = spectrum_.ptr<double>(l);
      double sum = 0;
      for (int k = 0; k < columns_; ++k) sum += sine[k] * row[k];
      height[l] = sum * per_column;
    }
  }
  // Into the column modes, each mode's extra x extra inverse, and back.
  std::vector<double> in_modes(static_cast<std::size_t>(extra) * ny_), cancelling(in_modes.size());
  for (int j = 0; j < ny_; ++j) {
    const double* mode = column_modes_.ptr<double>(j);
    for (int a = 0; a < extra; ++a) {
      const double* height = extra_height_.ptr<double>(a);
      double sum = 0;
      for (int l = 0; l < ny_; ++l) sum += mode[l] * height[l];
      in_modes[a * ny_ + j] = sum;
    }
    const double* inverse = response_inverse_.ptr<double>(j);
    for (int b = 0; b < extra; ++b) {
      double sum = 0;
      for (int a = 0; a < extra; ++a) sum += inverse[b * extra + a] * in_modes[a * ny_ + j];
      cancelling[b * ny_ + j] = -sum;
    }
  }
  source_.setTo(0);
  for (int j = 0; j < ny_; ++j) {
    const double* mode = column_modes_.ptr<double>(j);
    for (int b = 0; b < extra; ++b) {
      double* source = source_.ptr<double>(b);
      const double weight = cancelling[b * ny_ + j];
      for (int l = 0; l < ny_; ++l) source[l] += weight * mode[l];
    }
  }
  // The sources' own solution: 2 sin_a(k) s_a(l) through every column's system.
  for (int l = 0; l < ny_; ++l) {
    double* row = correction_.ptr<double>(l);
    for (int k = 0; k < columns_; ++k) row[k] = 0;
    for (int a = 0; a < extra; ++a) {
      const double* sine = extra_sine_.ptr<double>(a);
      const double s = 2 * source_.at<double>(a, l);
      for (int k = 0; k < columns_; ++k) row[k] += s * sine[k];
    }
  }
  solve_columns(correction_);
  spectrum_ += correction_;
}

cv::Mat DstPoisson::solve(const cv::Mat& p, const cv::Mat& q) {
  cv::Mat height;
  solve(p, q, height);
  return height;
}

void DstPoisson::solve(const cv::Mat& p, const cv::Mat& q, cv::Mat& height) {
  CV_Assert(p.type() == CV_64FC1 && p.rows == height_ && p.cols == width_ - 1);
  CV_Assert(q.type() == CV_64FC1 && q.rows == height_ - 1 && q.cols == width_);
  // The divergence of the gradients on the interior: the 5-point Laplacian
  // of H (the extra columns stay zero), transformed as it is made.
  transform([&](int l, double* out) {
    const int v = l + 1;
    const double* pr = p.ptr<double>(v);
    const double* qr = q.ptr<double>(v);
    const double* qu = q.ptr<double>(v - 1);
    for (int u = 1; u <= nx_; ++u) out[u - 1] = pr[u] - pr[u - 1] + qr[u] - qu[u];
    for (int k = nx_; k < columns_; ++k) out[k] = 0;
  });
  transformed_rows(columns_, [&](int l, int k, double value) { spectrum_.at<double>(l, k) = value; });
  solve_columns(spectrum_);
  if (columns_ > nx_) cancel_extra_columns();
  // The sine transform applied twice scales by 2 (columns + 1); the extra
  // columns are left out.
  transform([&](int l, double* out) {
    const double* in = spectrum_.ptr<double>(l);
    std::copy(in, in + columns_, out);
  });
  const double scale = 1.0 / period_;
  height.create(height_, width_, CV_64FC1);
  height.row(0).setTo(0);
  height.row(height_ - 1).setTo(0);
  for (int v = 1; v <= ny_; ++v) height.at<double>(v, 0) = height.at<double>(v, width_ - 1) = 0;
  transformed_rows(nx_, [&](int l, int k, double value) { height.at<double>(l + 1, k + 1) = value * scale; });
}

}  // namespace touchcloud::imaging
