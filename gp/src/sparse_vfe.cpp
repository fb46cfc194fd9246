#include "touchcloud/gp/sparse_vfe.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/Dense>

#include "latent_variance.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {

SparseVfeGp::SparseVfeGp(KernelKind kind, const Hyperparameters& h, JitterSchedule jitter)
    : kernel_(kind, h), jitter_(jitter) {
  jitter_.validate();
  if (!(h.noise_variance_mm2 > 0)) {
    std::ostringstream msg;
    msg << "sparse VFE GP: noise_variance_mm2 = " << h.noise_variance_mm2 << " must be > 0";
    throw InputError(msg.str());
  }
}

void SparseVfeGp::fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                      const Eigen::MatrixX2d& inducing_xy_mm) {
  check_training(xy_mm, z_mm, "training point");
  check_finite(inducing_xy_mm, "inducing point");
  if (inducing_xy_mm.rows() == 0) throw InputError("sparse VFE GP: no inducing points");
  centring_ = centring_of(xy_mm, z_mm);
  n_ = xy_mm.rows();
  const CentredXy p = centre(xy_mm, centring_);
  CentredXy u = centre(inducing_xy_mm, centring_);
  ux_ = std::move(u.x);
  uy_ = std::move(u.y);
  const Eigen::Index m = ux_.size();
  const Eigen::VectorXd z = z_mm.array() - centring_.z_mm;
  const double noise = kernel_.hyperparameters().noise_variance_mm2, sigma = std::sqrt(noise);

  l_uu_.resize(m, m);
  kuu_report_ = factor_with_jitter(
      l_uu_, [&](Eigen::Ref<Eigen::MatrixXd> a) { kernel_.fill_lower(ux_, uy_, 0.0, a); }, jitter_,
      "sparse VFE GP inducing covariance");
  l_uu_.triangularView<Eigen::StrictlyUpper>().setZero();

  Eigen::MatrixXd a(m, n_);
  kernel_.fill_cross(ux_, uy_, p.x, p.y, a);
  l_uu_.triangularView<Eigen::Lower>().solveInPlace(a);
  a /= sigma;
  l_b_ = Eigen::MatrixXd::Identity(m, m);
  l_b_.selfadjointView<Eigen::Lower>().rankUpdate(a);
  const double trace_aat = l_b_.diagonal().sum() - static_cast<double>(m);
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(l_b_);
  if (llt.info() != Eigen::Success)  // I + A A^T has eigenvalues >= 1; failure means corrupt input
    throw RunError("sparse VFE GP: Cholesky of I + A A^T failed");
  l_b_.triangularView<Eigen::StrictlyUpper>().setZero();

  Eigen::VectorXd c = a * z / sigma;
  l_b_.triangularView<Eigen::Lower>().solveInPlace(c);
  const double nd = static_cast<double>(n_);
  const double trace_k = nd * kernel_.prior_variance_mm2();
  bound_ = -0.5 * nd * std::log(2.0 * std::numbers::pi) - l_b_.diagonal().array().log().sum() -
           0.5 * nd * std::log(noise) - 0.5 * z.squaredNorm() / noise + 0.5 * c.squaredNorm() -
           0.5 * trace_k / noise + 0.5 * trace_aat;

  weights_ = c;
  l_b_.triangularView<Eigen::Lower>().transpose().solveInPlace(weights_);
  l_uu_.triangularView<Eigen::Lower>().transpose().solveInPlace(weights_);
}

Eigen::VectorXd SparseVfeGp::mean(const Eigen::MatrixX2d& xy_mm) const {
  check_finite(xy_mm, "query point");
  if (n_ == 0) return Eigen::VectorXd::Constant(xy_mm.rows(), centring_.z_mm);
  const CentredXy q = centre(xy_mm, centring_);
  return kernel_.weighted_sums(ux_, uy_, weights_, q.x, q.y).array() + centring_.z_mm;
}

Eigen::VectorXd SparseVfeGp::variance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count) const {
  check_finite(xy_mm, "query point");
  Eigen::VectorXd out = Eigen::VectorXd::Constant(xy_mm.rows(), kernel_.prior_variance_mm2());
  std::size_t clamped = 0;
  if (n_ > 0 && xy_mm.rows() > 0) {
    const CentredXy q = centre(xy_mm, centring_);
    Eigen::MatrixXd w(ux_.size(), xy_mm.rows());
    kernel_.fill_cross(ux_, uy_, q.x, q.y, w);
    l_uu_.triangularView<Eigen::Lower>().solveInPlace(w);  // L_uu^-1 K_u*
    out -= w.colwise().squaredNorm().transpose();
    l_b_.triangularView<Eigen::Lower>().solveInPlace(w);  // L_B^-1 L_uu^-1 K_u*
    out += w.colwise().squaredNorm().transpose();
    clamped = clamp_latent_variance(out, "sparse VFE GP", n_);
  }
  if (clamped_count) *clamped_count = clamped;
  return out;
}

Eigen::MatrixXd SparseVfeGp::covariance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count) const {
  check_finite(xy_mm, "query point");
  const Eigen::Index m = xy_mm.rows();
  Eigen::MatrixXd out(m, m);
  const CentredXy q = centre(xy_mm, centring_);
  kernel_.fill_lower(q.x, q.y, 0.0, out);
  if (n_ > 0 && m > 0) {
    Eigen::MatrixXd w(ux_.size(), m);
    kernel_.fill_cross(ux_, uy_, q.x, q.y, w);
    l_uu_.triangularView<Eigen::Lower>().solveInPlace(w);
    out.selfadjointView<Eigen::Lower>().rankUpdate(w.transpose(), -1.0);
    l_b_.triangularView<Eigen::Lower>().solveInPlace(w);
    out.selfadjointView<Eigen::Lower>().rankUpdate(w.transpose(), 1.0);
  }
  const std::size_t clamped = clamp_latent_covariance(out, "sparse VFE GP", n_);
  if (clamped_count) *clamped_count = clamped;
  return out;
}

}  // namespace touchcloud::gp
