#include "touchcloud/gp/kernel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "touchcloud/gp/matern_sums.hpp"
#include "touchcloud/gp/triangle_columns.hpp"
#include "touchcloud/gp/two_threads.hpp"
#include "touchcloud/gp/vector_exp.hpp"

namespace touchcloud::gp {

namespace {
constexpr double kSqrt5 = 2.23606797749978969640917366873128;
}

Kernel::Kernel(KernelKind kind, const Hyperparameters& h) : kind_(kind), h_(h) {
  h_.validate("GP kernel");
  inv_lengthscale2_ = 1.0 / (h_.lengthscale_mm * h_.lengthscale_mm);
}

// With t = r^2 / l^2: RBF shape exp(-t/2), d/dlog l = t exp(-t/2).
// Matern 5/2 with s = sqrt(5 t): (1 + s + s^2/3) e^-s, d/dlog l = (s^2/3)(1 + s) e^-s.
// Neither divides by r, so both are exact at r = 0 (duplicates).
double Kernel::covariance(double r2_mm2) const {
  const double t = r2_mm2 * inv_lengthscale2_;
  if (kind_ == KernelKind::rbf) return h_.signal_variance_mm2 * std::exp(-0.5 * t);
  const double s = kSqrt5 * std::sqrt(t);
  return h_.signal_variance_mm2 * (1.0 + s + s * s / 3.0) * std::exp(-s);
}

double Kernel::d_covariance_d_log_lengthscale(double r2_mm2) const {
  const double t = r2_mm2 * inv_lengthscale2_;
  if (kind_ == KernelKind::rbf) return h_.signal_variance_mm2 * t * std::exp(-0.5 * t);
  const double s = kSqrt5 * std::sqrt(t);
  return h_.signal_variance_mm2 * (s * s / 3.0) * (1.0 + s) * std::exp(-s);
}

// The exponentials go through exp_in_place (vector_exp.hpp): most of the
// cost of building a kernel matrix.
void Kernel::covariance_in_place(Eigen::Map<Eigen::ArrayXd> v) const {
  const double s2 = h_.signal_variance_mm2;
  if (kind_ == KernelKind::rbf) {
    v *= -0.5 * inv_lengthscale2_;
    exp_in_place(v);
    v *= s2;
  } else {
    // In chunks, with e^-s on the stack: no allocation per call. The chunk is
    // a multiple of exp_in_place's width, so every value takes the same
    // exponential as in one pass.
    constexpr Eigen::Index kChunk = 256;
    std::array<double, kChunk> buffer;
    for (Eigen::Index first = 0; first < v.size(); first += kChunk) {
      const Eigen::Index len = std::min(kChunk, v.size() - first);
      auto s = v.segment(first, len);
      Eigen::Map<Eigen::ArrayXd> e(buffer.data(), len);
      s = (s * (5.0 * inv_lengthscale2_)).sqrt();
      e = -s;
      exp_in_place(e);
      s = s2 * (1.0 + s + s.square() * (1.0 / 3.0)) * e;
    }
  }
}

void Kernel::covariance_and_d_log_lengthscale(Eigen::Map<Eigen::ArrayXd> v, Eigen::Map<Eigen::ArrayXd> dk) const {
  const double s2 = h_.signal_variance_mm2;
  if (kind_ == KernelKind::rbf) {
    dk = v * inv_lengthscale2_;  // t
    v = -0.5 * dk;
    exp_in_place(v);
    v *= s2;   // k
    dk *= v;   // t k
  } else {
    dk = (v * (5.0 * inv_lengthscale2_)).sqrt();  // s
    v = -dk;
    exp_in_place(v);
    const auto poly = 1.0 + dk + dk.square() * (1.0 / 3.0);
    v = s2 * poly * v;                                         // k
    dk = v * (dk.square() * (1.0 / 3.0)) * (1.0 + dk) / poly;  // (s^2/3)(1 + s) s2 e^-s
  }
}

void Kernel::fill_lower(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double diagonal_add,
                        Eigen::Ref<Eigen::MatrixXd> out) const {
  const Eigen::Index n = x.size();
  for_triangle_columns(n, [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index j = first; j < last; ++j) {
      const Eigen::Index len = n - j;
      Eigen::Map<Eigen::ArrayXd> col(out.col(j).data() + j, len);
      col = (x.segment(j, len).array() - x[j]).square() + (y.segment(j, len).array() - y[j]).square();
      covariance_in_place(col);
      col[0] += diagonal_add;
    }
  });
}

Eigen::VectorXd Kernel::weighted_sums(const Eigen::VectorXd& px, const Eigen::VectorXd& py, const Eigen::VectorXd& w,
                                      const Eigen::Ref<const Eigen::VectorXd>& qx,
                                      const Eigen::Ref<const Eigen::VectorXd>& qy) const {
  const Eigen::Index n = px.size(), m = qx.size();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(m);
  if (n == 0) return out;
  const auto queries = [&](Eigen::Index first, Eigen::Index last) {
    // Matern 5/2 in one fused pass where the CPU allows (matern_sums.hpp).
    if (kind_ == KernelKind::matern52 && matern52_unit_sums(px.data(), py.data(), w.data(), n, qx.data(), qy.data(),
                                                            first, last, 5.0 * inv_lengthscale2_, out.data())) {
      out.segment(first, last - first) *= h_.signal_variance_mm2;
      return;
    }
    Eigen::MatrixXd column(n, 1);
    for (Eigen::Index j = first; j < last; ++j) {
      fill_cross(px, py, qx.segment(j, 1), qy.segment(j, 1), column);
      out[j] = column.col(0).dot(w);
    }
  };
  on_two_threads(m, m / 2, m * n, queries);
  return out;
}

void Kernel::fill_cross(const Eigen::VectorXd& px, const Eigen::VectorXd& py, const Eigen::Ref<const Eigen::VectorXd>& qx,
                        const Eigen::Ref<const Eigen::VectorXd>& qy, Eigen::Ref<Eigen::MatrixXd> out) const {
  const Eigen::Index n = px.size();
  for (Eigen::Index j = 0; j < qx.size(); ++j) {
    Eigen::Map<Eigen::ArrayXd> col(out.col(j).data(), n);
    col = (px.array() - qx[j]).square() + (py.array() - qy[j]).square();
    covariance_in_place(col);
  }
}

}  // namespace touchcloud::gp
