#include "touchcloud/gp/marginal_likelihood.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "touchcloud/gp/cholesky_inverse.hpp"
#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/gp/huge_pages.hpp"
#include "touchcloud/gp/kernel.hpp"
#include "touchcloud/gp/training_data.hpp"
#include "touchcloud/gp/triangle_columns.hpp"

namespace touchcloud::gp {

namespace {
double half_n_log_2pi(Eigen::Index n) { return 0.5 * static_cast<double>(n) * std::log(2.0 * std::numbers::pi); }
}  // namespace

MarginalLikelihood::MarginalLikelihood(KernelKind kind, const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                                       JitterSchedule jitter, PriorMean level)
    : kind_(kind), jitter_(jitter) {
  check_training(xy_mm, z_mm, "training point");
  jitter_.validate();
  const Centring c = centring_of(xy_mm, z_mm, level);
  CentredXy p = centre(xy_mm, c);
  x_ = std::move(p.x);
  y_ = std::move(p.y);
  z_ = z_mm.array() - c.z_mm;
}

void MarginalLikelihood::factorise(const Hyperparameters& h) {
  const Eigen::Index n = x_.size();
  if (work_.rows() != n) {
    work_.resize(n, n);
    advise_huge_pages(work_);
    factor_held_ = false;
  }
  if (factor_held_ && held_h_ == h) return;
  factor_held_ = false;  // work_ is about to change
  const Kernel kernel(kind_, h);
  held_report_ = factor_with_jitter(
      work_, [&](Eigen::Ref<Eigen::MatrixXd> a) { kernel.fill_lower(x_, y_, h.noise_variance_mm2, a); }, jitter_,
      "GP log marginal likelihood");
  alpha_ = z_;
  solve_lower_in_place(work_, alpha_);
  solve_lower_transposed_in_place(work_, alpha_);
  quad_ = z_.dot(alpha_);
  half_log_det_ = work_.diagonal().array().log().sum();
  factor_held_ = true;
  held_h_ = h;
}

MarginalLikelihood::GradientTerms MarginalLikelihood::gradient_terms(const Hyperparameters& h) {
  factorise(h);
  factor_held_ = false;
  // work_ now becomes A^-1; kernel values and derivatives are recomputed per
  // column from the distances, so no second n x n buffer is needed.
  cholesky_inverse_in_place(work_);
  const Kernel kernel(kind_, h);
  const Eigen::Index n = x_.size();
  // Each column's four sums, on two threads; added up in column order
  // below, so the totals do not depend on the split.
  Eigen::Array4Xd per_column(4, n);
  for_triangle_columns(n, [&](Eigen::Index first, Eigen::Index last) {
    Eigen::ArrayXd k_col(n), dk_col(n), a_col(n);
    for (Eigen::Index j = first; j < last; ++j) {
      const Eigen::Index len = n - j;
      Eigen::Map<Eigen::ArrayXd> k(k_col.data(), len), dk(dk_col.data(), len), a(a_col.data(), len);
      k = (x_.segment(j, len).array() - x_[j]).square() + (y_.segment(j, len).array() - y_[j]).square();
      kernel.covariance_and_d_log_lengthscale(k, dk);
      a = alpha_.segment(j, len).array() * alpha_[j];
      const auto inverse = work_.col(j).segment(j, len).array();
      // Symmetric sums over the lower triangle: twice the column, less the diagonal once.
      per_column.col(j) << 2.0 * (a * k).sum() - a[0] * k[0], 2.0 * (inverse * k).sum() - inverse[0] * k[0],
          2.0 * (a * dk).sum() - a[0] * dk[0], 2.0 * (inverse * dk).sum() - inverse[0] * dk[0];
    }
  });
  GradientTerms t;
  for (Eigen::Index j = 0; j < n; ++j) {
    t.quad_k += per_column(0, j);
    t.trace_k += per_column(1, j);
    t.quad_dl += per_column(2, j);
    t.trace_dl += per_column(3, j);
  }
  t.quad_i = alpha_.squaredNorm();
  t.trace_i = work_.diagonal().sum();
  return t;
}

LmlEvaluation MarginalLikelihood::evaluate(const Hyperparameters& h, bool with_gradient) {
  LmlEvaluation out;
  const Eigen::Index n = x_.size();
  if (n == 0) return out;
  factorise(h);
  out.factorisation = held_report_;
  out.lml = -0.5 * quad_ - half_log_det_ - half_n_log_2pi(n);
  if (!with_gradient) return out;
  const GradientTerms t = gradient_terms(h);
  out.gradient << 0.5 * (t.quad_k - t.trace_k), 0.5 * (t.quad_dl - t.trace_dl),
      0.5 * h.noise_variance_mm2 * (t.quad_i - t.trace_i);
  return out;
}

ProfiledEvaluation MarginalLikelihood::evaluate_profiled(double lengthscale_mm, double noise_ratio,
                                                         const HyperparameterBounds& bounds, bool with_gradient) {
  const double s2_lo = bounds.lower.signal_variance_mm2, s2_hi = bounds.upper.signal_variance_mm2;
  const double noise_lo = bounds.lower.noise_variance_mm2, noise_hi = bounds.upper.noise_variance_mm2;
  const double g = std::clamp(noise_ratio, noise_lo / s2_hi, noise_hi / s2_lo);
  const Hyperparameters unit{1.0, lengthscale_mm, g};
  const Eigen::Index n = x_.size();
  ProfiledEvaluation out;
  out.hyperparameters = unit;
  if (n == 0) return out;
  factorise(unit);
  out.factorisation = held_report_;

  // The best s2 on the feasible interval (not empty for g in the range above);
  // the LML is concave in log s2, so clamping the free maximum finds it.
  const double lo = std::max(s2_lo, noise_lo / g), hi = std::min(s2_hi, noise_hi / g);
  const double free = quad_ / static_cast<double>(n);
  const double s2 = std::clamp(free, lo, std::max(lo, hi));
  const bool at_noise_bound = (free < lo && noise_lo / g > s2_lo) || (free > hi && noise_hi / g < s2_hi);
  out.hyperparameters.signal_variance_mm2 = s2;
  out.hyperparameters.noise_variance_mm2 = std::clamp(g * s2, noise_lo, noise_hi);
  out.lml = -0.5 * quad_ / s2 - 0.5 * static_cast<double>(n) * std::log(s2) - half_log_det_ - half_n_log_2pi(n);
  if (!with_gradient) return out;

  // Partial derivatives of the LML at A = s2 R in log (s2, l, noise); with
  // s2 free or at its own bound, d/dlog g is the noise partial (the s2 partial
  // is zero or s2 does not move); at a noise bound the noise stays and s2
  // moves against g.
  const GradientTerms t = gradient_terms(unit);
  const double d_signal = 0.5 * (t.quad_k / s2 - t.trace_k);
  const double d_lengthscale = 0.5 * (t.quad_dl / s2 - t.trace_dl);
  const double d_noise = 0.5 * g * (t.quad_i / s2 - t.trace_i);
  out.gradient << d_lengthscale, at_noise_bound ? -d_signal : d_noise;
  return out;
}

}  // namespace touchcloud::gp
