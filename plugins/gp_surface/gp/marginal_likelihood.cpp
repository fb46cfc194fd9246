#include "gp/marginal_likelihood.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "gp/cholesky_inverse.hpp"
#include "gp/factor_algebra.hpp"
#include "gp/kernel.hpp"
#include "gp/training_data.hpp"

namespace touchcloud::gp {

MarginalLikelihood::MarginalLikelihood(KernelKind kind, const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                                       JitterSchedule jitter)
    : kind_(kind), jitter_(jitter) {
  check_training(xy_mm, z_mm, "training point");
  jitter_.validate();
  const Centring c = centring_of(xy_mm, z_mm);
  CentredXy p = centre(xy_mm, c);
  x_ = std::move(p.x);
  y_ = std::move(p.y);
  z_ = z_mm.array() - c.z_mm;
}

LmlEvaluation MarginalLikelihood::evaluate(const Hyperparameters& h, bool with_gradient) {
  const Kernel kernel(kind_, h);
  const Eigen::Index n = x_.size();
  LmlEvaluation out;
  if (n == 0) return out;
  if (work_.rows() != n) {
    work_.resize(n, n);
    factor_held_ = false;
  }

  Eigen::VectorXd alpha;
  if (factor_held_ && held_h_ == h) {
    out = held_;
    alpha = held_alpha_;
  } else {
    factor_held_ = false;  // work_ is about to change
    out.factorisation = factor_with_jitter(
        work_, [&](Eigen::Ref<Eigen::MatrixXd> a) { kernel.fill_lower(x_, y_, h.noise_variance_mm2, a); }, jitter_,
        "GP log marginal likelihood");
    alpha = z_;
    solve_lower_in_place(work_, alpha);
    solve_lower_transposed_in_place(work_, alpha);
    out.lml = -0.5 * z_.dot(alpha) - work_.diagonal().array().log().sum() -
              0.5 * static_cast<double>(n) * std::log(2.0 * std::numbers::pi);
  }
  if (!with_gradient) {
    factor_held_ = true;
    held_h_ = h;
    held_ = out;
    held_alpha_ = alpha;
    return out;
  }
  factor_held_ = false;

  // work_ now becomes A^-1; kernel values and derivatives are recomputed per
  // column from the distances, so no second n x n buffer is needed.
  cholesky_inverse_in_place(work_);
  double g_signal = 0.0, g_lengthscale = 0.0;
  Eigen::ArrayXd k_col(n), dk_col(n), w_col(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index len = n - j;
    Eigen::Map<Eigen::ArrayXd> k(k_col.data(), len), dk(dk_col.data(), len), w(w_col.data(), len);
    k = (x_.segment(j, len).array() - x_[j]).square() + (y_.segment(j, len).array() - y_[j]).square();
    kernel.covariance_and_d_log_lengthscale(k, dk);
    // Weights of the symmetric sum over the lower triangle: 2 off the diagonal.
    w = alpha.segment(j, len).array() * alpha[j] - work_.col(j).segment(j, len).array();
    w.tail(len - 1) *= 2.0;
    g_signal += (w * k).sum();  // dA/dlog s2 = K (noise-free part)
    g_lengthscale += (w * dk).sum();
  }
  const double trace_inverse = work_.diagonal().sum();
  out.gradient << 0.5 * g_signal, 0.5 * g_lengthscale,
      0.5 * h.noise_variance_mm2 * (alpha.squaredNorm() - trace_inverse);
  return out;
}

}  // namespace touchcloud::gp
