#include "implicit_selection.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>

#include "touchcloud/error.hpp"
#include "touchcloud/gp/cholesky_inverse.hpp"

namespace touchcloud::gp {

namespace {

// -1/2 r^T A^-1 r - 1/2 log|A| - m/2 log 2 pi with A = K + (noise + jitter) I,
// and 1/2 tr((alpha alpha^T - A^-1) dA/dtheta) for its gradient.
bool evaluate_implicit_lml(ImplicitKernelKind kind, const Eigen::MatrixX3d& p, const Eigen::VectorXd& r,
              const JitterSchedule& jitter, const LogHyperparameters& theta, double& lml, Eigen::Vector3d* gradient) {
  const Hyperparameters h = from_log(theta);
  const ImplicitKernel kernel(kind, h);
  const Eigen::Index m = p.rows();
  Eigen::MatrixXd dist(m, m);
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = j; i < m; ++i) dist(i, j) = (p.row(i) - p.row(j)).norm();
  Eigen::MatrixXd a(m, m);
  CholeskyReport report;
  try {
    report = factor_with_jitter(
        a,
        [&](Eigen::Ref<Eigen::MatrixXd> out) {
          for (Eigen::Index j = 0; j < m; ++j)
            for (Eigen::Index i = j; i < m; ++i) out(i, j) = kernel.covariance(dist(i, j));
          out.diagonal().array() += h.noise_variance_mm2;
        },
        jitter, "implicit surface likelihood");
  } catch (const RunError&) {
    return false;
  }
  const Eigen::MatrixXd& factor = a;
  const auto l = factor.triangularView<Eigen::Lower>();
  const Eigen::VectorXd v = l.solve(r);
  const Eigen::VectorXd alpha = l.transpose().solve(v);
  lml = -0.5 * v.squaredNorm() - a.diagonal().array().log().sum() - 0.5 * m * std::log(2 * std::numbers::pi);
  if (!std::isfinite(lml)) return false;
  if (!gradient) return true;
  Eigen::MatrixXd& inverse = a;  // its lower triangle: L, then A^-1
  cholesky_inverse_in_place(inverse);
  gradient->setZero();
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = j; i < m; ++i) {
      const double w = (alpha[i] * alpha[j] - inverse(i, j)) * (i == j ? 0.5 : 1.0);
      (*gradient)[0] += w * kernel.covariance(dist(i, j));
      (*gradient)[1] += w * kernel.d_covariance_d_log_scale(dist(i, j));
      if (i == j) (*gradient)[2] += w * h.noise_variance_mm2;
    }
  return gradient->allFinite();
}

}  // namespace

SearchResult select_implicit_hyperparameters(const Eigen::MatrixX3d& p, const Eigen::VectorXd& r, double diameter_mm,
                                             const ImplicitSurfaceOptions& options) {
  const double diameter = std::max(diameter_mm, options.offset_mm);
  const double spread = std::max(r.squaredNorm() / static_cast<double>(r.size()), options.offset_mm * options.offset_mm);
  HyperparameterBounds bounds;
  bounds.lower.signal_variance_mm2 = 1e-3 * spread;
  bounds.upper.signal_variance_mm2 = 1e3 * spread;
  bounds.lower.noise_variance_mm2 = options.min_noise_mm * options.min_noise_mm;
  bounds.upper.noise_variance_mm2 = options.max_noise_mm * options.max_noise_mm;
  Hyperparameters start{spread, 0, std::sqrt(bounds.lower.noise_variance_mm2 * bounds.upper.noise_variance_mm2)};
  if (options.kernel == ImplicitKernelKind::thin_plate) {
    bounds.lower.lengthscale_mm = diameter;
    bounds.upper.lengthscale_mm = 4 * diameter;
    start.lengthscale_mm = 1.5 * diameter;
  } else {
    bounds.lower.lengthscale_mm = options.offset_mm;
    bounds.upper.lengthscale_mm = 4 * diameter;
    start.lengthscale_mm = std::max(diameter / 4, options.offset_mm);
  }
  SearchOptions search;
  search.max_iterations = options.max_iterations;
  search.function_tolerance = 1e-7;  // the surface moves by far less than the offset below this
  search.jitter = options.jitter;
  const LmlFunction f = [&](const LogHyperparameters& theta, double& lml, Eigen::Vector3d* gradient) {
    return evaluate_implicit_lml(options.kernel, p, r, options.jitter, theta, lml, gradient);
  };
  return maximise_lml(f, bounds, {start}, search);
}

SearchResult select_implicit_on_training(const ImplicitTraining& data, const Eigen::Vector3d& centre, double radius,
                                         const ImplicitSurfaceOptions& options, double scale_floor,
                                         Eigen::Index& subset_size) {
  const Eigen::Index m = std::min(data.n, options.selection_points);
  Eigen::MatrixX3d p(m, 3);
  Eigen::VectorXd r(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::Index i = j * data.n / m;  // evenly strided: contacts and signed points of every touch
    p.row(j) = data.x.row(i);
    r[j] = data.f[i] - ((data.x.row(i).transpose() - centre).norm() - radius);
  }
  subset_size = m;
  return select_implicit_hyperparameters(p, r, scale_floor * data.diameter_mm(), options);
}

}  // namespace touchcloud::gp
