#include "gp/exact_gp.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/Dense>

#include "touchcloud/error.hpp"

namespace touchcloud::gp {

std::string to_string(UpdatePath path) { return path == UpdatePath::bordered ? "bordered" : "refactorised"; }

ExactGp::ExactGp(KernelKind kind, const Hyperparameters& h, ExactGpOptions options)
    : kernel_(kind, h), options_(options) {
  options_.jitter.validate();
}

void ExactGp::fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm) {
  check_training(xy_mm, z_mm, "training point");
  const bool any = xy_mm.rows() > 0;
  fit(xy_mm, z_mm, any ? centring_of(xy_mm, z_mm) : Centring{});
  centring_fixed_ = any;
}

void ExactGp::fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, const Centring& centring) {
  check_training(xy_mm, z_mm, "training point");
  centring_ = centring;
  centring_fixed_ = true;
  CentredXy p = centre(xy_mm, centring_);
  x_ = std::move(p.x);
  y_ = std::move(p.y);
  z_ = z_mm.array() - centring_.z_mm;
  n_ = 0;  // the old factor is not kept
  ensure_capacity(xy_mm.rows());
  n_ = xy_mm.rows();
  refactorise();
}

void ExactGp::refactorise() {
  const double noise = kernel_.hyperparameters().noise_variance_mm2;
  try {
    factorisation_ = factor_with_jitter(
        factor(), [&](Eigen::Ref<Eigen::MatrixXd> a) { kernel_.fill_lower(x_, y_, noise, a); }, options_.jitter,
        "GP surface fit");
  } catch (const RunError&) {
    // The failed attempts overwrote the factor: fall back to the prior rather
    // than keep a model that would answer from garbage.
    n_ = 0;
    x_.resize(0);
    y_.resize(0);
    z_.resize(0);
    v_.resize(0);
    alpha_.resize(0);
    factorisation_ = {};
    throw;
  }
  v_ = z_;
  factor().triangularView<Eigen::Lower>().solveInPlace(v_);
  alpha_ = v_;
  factor().triangularView<Eigen::Lower>().transpose().solveInPlace(alpha_);
}

void ExactGp::reserve(Eigen::Index points) {
  if (points <= storage_.rows()) return;
  Eigen::MatrixXd grown(points, points);
  grown.topLeftCorner(n_, n_).triangularView<Eigen::Lower>() = factor().triangularView<Eigen::Lower>();
  storage_.swap(grown);
}

void ExactGp::ensure_capacity(Eigen::Index points) {
  if (points <= storage_.rows()) return;
  reserve(points + static_cast<Eigen::Index>(options_.capacity_slack * static_cast<double>(points)));
}

UpdateReport ExactGp::add_points(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm) {
  check_training(xy_mm, z_mm, "added training point");
  const Eigen::Index k = xy_mm.rows(), n = n_;
  UpdateReport report;
  report.points_added = k;
  report.factorisation = factorisation_;
  if (k == 0) return report;

  if (!centring_fixed_) centring_ = centring_of(xy_mm, z_mm);
  centring_fixed_ = true;
  const CentredXy p = centre(xy_mm, centring_);
  const Eigen::VectorXd zc = z_mm.array() - centring_.z_mm;
  ensure_capacity(n + k);

  bool extended = false;
  if (n > 0) {
    // [L 0; L21 L22] with L21 = K21 L^-T and L22 L22^T = A22 - L21 L21^T
    // (the Schur complement). The strict upper triangle is free workspace.
    const double s2 = kernel_.hyperparameters().signal_variance_mm2;
    const double noise = kernel_.hyperparameters().noise_variance_mm2;
    auto l11 = storage_.topLeftCorner(n, n).triangularView<Eigen::Lower>();
    auto cross = storage_.block(0, n, n, k);
    kernel_.fill_cross(x_, y_, p.x, p.y, cross);
    l11.solveInPlace(cross);
    auto l21 = storage_.block(n, 0, k, n);
    l21 = cross.transpose();
    auto schur = storage_.block(n, n, k, k);
    kernel_.fill_lower(p.x, p.y, noise + factorisation_.jitter_mm2, schur);
    schur.selfadjointView<Eigen::Lower>().rankUpdate(l21, -1.0);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(schur);
    extended = llt.info() == Eigen::Success && pivots_above_rounding(schur, s2 + noise, n + k);
    if (extended) {
      Eigen::VectorXd v_new = zc - l21 * v_;
      schur.triangularView<Eigen::Lower>().solveInPlace(v_new);
      v_.conservativeResize(n + k);
      v_.tail(k) = v_new;
    }
  }

  x_.conservativeResize(n + k);
  y_.conservativeResize(n + k);
  z_.conservativeResize(n + k);
  x_.tail(k) = p.x;
  y_.tail(k) = p.y;
  z_.tail(k) = zc;
  n_ = n + k;

  if (extended) {
    alpha_ = v_;
    factor().triangularView<Eigen::Lower>().transpose().solveInPlace(alpha_);
    report.path = UpdatePath::bordered;
  } else {
    refactorise();
    report.path = UpdatePath::refactorised;
    report.reason = n == 0 ? "no earlier factor to extend"
                           : "the Schur complement of the new points is not positive definite "
                             "(e.g. a new point duplicates the data to rounding level)";
  }
  report.factorisation = factorisation_;
  return report;
}

Eigen::Index ExactGp::query_block() const {
  return std::max<Eigen::Index>(1, options_.query_block_doubles / std::max<Eigen::Index>(1, n_));
}

void ExactGp::for_each_cross_block(const Eigen::MatrixX2d& xy_mm, const CrossBlockFunction& f) const {
  const Eigen::Index m = xy_mm.rows();
  if (n_ == 0 || m == 0) return;
  const Eigen::Index block = std::min(query_block(), m);
  Eigen::MatrixXd k_cross(n_, block);
  for (Eigen::Index b0 = 0; b0 < m; b0 += block) {
    const Eigen::Index bs = std::min(block, m - b0);
    const Eigen::VectorXd qx = xy_mm.col(0).segment(b0, bs).array() - centring_.x_mm;
    const Eigen::VectorXd qy = xy_mm.col(1).segment(b0, bs).array() - centring_.y_mm;
    auto kb = k_cross.leftCols(bs);
    kernel_.fill_cross(x_, y_, qx, qy, kb);
    f(b0, kb);
  }
}

Eigen::VectorXd ExactGp::mean(const Eigen::MatrixX2d& xy_mm) const {
  check_finite(xy_mm, "query point");
  const Eigen::Index m = xy_mm.rows();
  Eigen::VectorXd out = Eigen::VectorXd::Constant(m, centring_.z_mm);
  for_each_cross_block(xy_mm, [&](Eigen::Index b0, CrossBlock kb) {
    out.segment(b0, kb.cols()).noalias() += kb.transpose() * alpha_;
  });
  return out;
}

Eigen::MatrixXd ExactGp::mean_on_grid(const Eigen::VectorXd& xs_mm, const Eigen::VectorXd& ys_mm) const {
  const Eigen::Index nx = xs_mm.size(), ny = ys_mm.size();
  Eigen::MatrixX2d xs_as_points(nx, 2), ys_as_points(ny, 2);
  xs_as_points << xs_mm, Eigen::VectorXd::Zero(nx);
  ys_as_points << Eigen::VectorXd::Zero(ny), ys_mm;
  check_finite(xs_as_points, "grid x value");
  check_finite(ys_as_points, "grid y value");
  if (n_ == 0 || kernel_kind() != KernelKind::rbf) {
    Eigen::MatrixX2d points(nx * ny, 2);
    for (Eigen::Index i = 0; i < nx; ++i) {
      points.col(0).segment(i * ny, ny).setConstant(xs_mm[i]);
      points.col(1).segment(i * ny, ny) = ys_mm;
    }
    const Eigen::VectorXd flat = mean(points);
    return Eigen::Map<const Eigen::MatrixXd>(flat.data(), ny, nx).transpose();
  }
  // exp(-(dx^2 + dy^2) / 2l^2) = exp(-dx^2 / 2l^2) exp(-dy^2 / 2l^2).
  const double l = kernel_.hyperparameters().lengthscale_mm, c = -0.5 / (l * l);
  Eigen::MatrixXd ex(nx, n_), ey(ny, n_);
  for (Eigen::Index p = 0; p < n_; ++p) {
    ex.col(p) = ((xs_mm.array() - centring_.x_mm - x_[p]).square() * c).exp() * alpha_[p];
    ey.col(p) = ((ys_mm.array() - centring_.y_mm - y_[p]).square() * c).exp();
  }
  Eigen::MatrixXd out = kernel_.hyperparameters().signal_variance_mm2 * (ex * ey.transpose());
  out.array() += centring_.z_mm;
  return out;
}

Eigen::VectorXd ExactGp::variance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count) const {
  check_finite(xy_mm, "query point");
  const Eigen::Index m = xy_mm.rows();
  const double prior = kernel_.prior_variance_mm2();
  Eigen::VectorXd out = Eigen::VectorXd::Constant(m, prior);
  std::size_t clamped = 0;
  if (n_ > 0 && m > 0) {
    for_each_cross_block(xy_mm, [&](Eigen::Index b0, CrossBlock kb) {
      factor().triangularView<Eigen::Lower>().solveInPlace(kb);
      out.segment(b0, kb.cols()) -= kb.colwise().squaredNorm().transpose();
    });
    for (Eigen::Index i = 0; i < m; ++i) {
      if (std::isnan(out[i])) {
        std::ostringstream msg;
        msg << "GP variance: NaN at query point " << i << " (the factor of " << n_ << " points is corrupt)";
        throw RunError(msg.str());
      }
      if (out[i] < 0.0) {  // rounding: k(x,x) and ||L^-1 k_x||^2 nearly cancel
        out[i] = 0.0;
        ++clamped;
      }
    }
  }
  if (clamped_count) *clamped_count = clamped;
  return out;
}

double ExactGp::log_marginal_likelihood() const {
  if (n_ == 0) return 0.0;
  return -0.5 * z_.dot(alpha_) - factor().diagonal().array().log().sum() -
         0.5 * static_cast<double>(n_) * std::log(2.0 * std::numbers::pi);
}

Eigen::MatrixXd ExactGp::cholesky_factor() const { return factor().triangularView<Eigen::Lower>(); }

}  // namespace touchcloud::gp
