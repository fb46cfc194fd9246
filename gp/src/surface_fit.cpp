#include "touchcloud/gp/surface_fit.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include "touchcloud/error.hpp"
#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/gp/hyperparameter_search.hpp"
#include "touchcloud/gp/inducing_points.hpp"
#include "touchcloud/gp/point_subset.hpp"
#include "touchcloud/gp/simd_path.hpp"
#include "touchcloud/gp/sparse_surface_model.hpp"
#include "touchcloud/gp/training_data.hpp"
#include "touchcloud/gp/vector_exp.hpp"

namespace touchcloud::gp {

namespace {

// Fewer points leave no lengthscale to select: the GP then runs at set values.
constexpr Eigen::Index kMinSelectionPoints = 3;
constexpr double kInitialNoiseVarianceMm2 = 0.01;
// Hyperparameters to ~0.1 %: the surface cannot tell them apart.
constexpr double kSelectionStopGain = 1e-6;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

const char* to_string(TouchPath path) {
  switch (path) {
    case TouchPath::unchanged: return "unchanged";
    case TouchPath::bordered: return "bordered";
    case TouchPath::refactorised: return "refactorised";
    case TouchPath::selected: return "selected";
  }
  return "?";
}

SurfaceFit::SurfaceFit(const Options& options) {
  if (const auto problem = options.problem()) throw InputError("GP surface fit: " + problem->text());
  summary_.given = options;
  set_factor_algebra_threads(options.blas_threads.value_or(0));
  summary_.blas_threads = factor_algebra_threads();
  summary_.dense_algebra = factor_algebra_backend();
  summary_.kernel_exp = vector_exp_path();
  if (options.kernel == KernelKind::matern52) {
    const SimdPath sums = fastest_simd_path();
    summary_.matern_mean_sums =
        sums == SimdPath::none ? std::string("kernel columns (Eigen)") : std::string(to_string(sums)) + " (inline exp)";
  }
}

// The touch is checked before it joins the training set: a non-finite
// point would stay there and fail every later fit.
void SurfaceFit::append(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm) {
  check_training(xy_mm, z_mm, "point of this touch");
  const Eigen::Index n0 = xy_.rows();
  const Eigen::Index k = xy_mm.rows();
  xy_.conservativeResize(n0 + k, 2);
  z_.conservativeResize(n0 + k);
  xy_.bottomRows(k) = xy_mm;
  z_.tail(k) = z_mm;
}

// Hyperparameters for all the points, from a subset when asked; warm-started
// (with the last selection's curvature) after the first.
SelectionSummary SurfaceFit::select() {
  const Options& o = summary_.given;
  SearchOptions search;
  search.kernel = o.kernel;
  search.screening_points = o.screening_points;
  search.bounds.noise_sd_max = o.max_noise_mm;
  search.bounds.noise_sd_min = o.min_noise_mm;
  search.bounds.lengthscale_max_mm = o.max_lengthscale_mm;
  search.prior_mean = o.prior_mean;
  search.stop_gain = kSelectionStopGain;
  if (selected_at_ > 0) {
    search.start_hyperparameters = {last_};
    search.start_hessian_per_point = last_curvature_;
  }
  const auto started = std::chrono::steady_clock::now();
  const Eigen::Index n = xy_.rows();
  const Eigen::Index limit =
      o.selection_points > 0 ? o.selection_points : (o.method == FitMethod::sparse ? o.inducing_points : n);
  // Runs of consecutive points (parts of single touches) spread evenly
  // over the data keep the touches' point density (point_subset.hpp).
  const auto [sub_xy, sub_z] = subset_of_runs(xy_, z_, limit, o.selection_runs);
  const SearchResult r = select_hyperparameters(sub_xy, sub_z, search);
  last_ = r.hyperparameters;
  last_curvature_ = r.hessian_per_point;
  selected_at_ = n;
  ++summary_.selections;
  SelectionSummary s;
  s.points = std::min(limit, n);
  s.lml = r.lml;
  s.hyperparameters = r.hyperparameters;
  s.evaluations = r.evaluations;
  for (const StartReport& start : r.screening) s.evaluations += start.evaluations;
  for (const StartReport& level : r.refinement) s.evaluations += level.evaluations;
  s.seconds = seconds_since(started);
  return s;
}

std::optional<std::array<double, 2>> SurfaceFit::data_z_range() const {
  if (z_.size() == 0) return std::nullopt;
  return std::array<double, 2>{z_.minCoeff(), z_.maxCoeff()};
}

void SurfaceFit::fit_exact(const Hyperparameters& h) {
  ExactGpOptions options;
  options.prior_mean = summary_.given.prior_mean;
  auto model = std::make_shared<ExactGp>(summary_.given.kernel, h, options);
  model->fit(xy_, z_);
  gp_ = model;
}

SurfaceModelPtr SurfaceFit::fit_sparse(const Hyperparameters& h, std::mt19937_64& rng, TouchSummary& touch) {
  const Eigen::Index n = xy_.rows();
  const Eigen::Index first = std::uniform_int_distribution<Eigen::Index>(0, n - 1)(rng);
  const std::vector<Eigen::Index> rows = farthest_point_subset(xy_, summary_.given.inducing_points, first);
  Eigen::MatrixX2d inducing(static_cast<Eigen::Index>(rows.size()), 2);
  for (std::size_t i = 0; i < rows.size(); ++i) inducing.row(static_cast<Eigen::Index>(i)) = xy_.row(rows[i]);
  auto model = std::make_shared<SparseVfeGp>(summary_.given.kernel, h);
  model->fit(xy_, z_, inducing);
  touch.inducing_points = inducing.rows();
  touch.vfe_bound = model->log_marginal_likelihood_bound();
  return std::make_shared<SparseSurfaceModel>(model, data_z_range());
}

SurfaceModelPtr SurfaceFit::add(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, std::mt19937_64& rng) {
  const auto started = std::chrono::steady_clock::now();
  const Options& o = summary_.given;
  const Eigen::Index n0 = xy_.rows();
  append(xy_mm, z_mm);
  const Eigen::Index n = xy_.rows();
  TouchSummary touch;
  touch.points_added = n - n0;
  touch.training_points = n;
  Hyperparameters h = last_;
  if (n < kMinSelectionPoints) {
    // Too few points to select hyperparameters: a GP at set values.
    h = {};
    h.lengthscale_mm = o.initial_lengthscale_mm;
    h.noise_variance_mm2 = kInitialNoiseVarianceMm2;
    fit_exact(h);  // method sparse too: with no point there is nothing to choose inducing points from
  } else if (selected_at_ == 0 || static_cast<double>(n) >= (1.0 + o.reselect_growth) * static_cast<double>(selected_at_)) {
    touch.selection = select();
    h = last_;
    if (o.method == FitMethod::exact) fit_exact(h);
    touch.path = TouchPath::selected;
  } else if (o.method == FitMethod::exact && n > n0) {
    auto model = std::make_shared<ExactGp>(*gp_);  // shares the factor; the previous model stays as it was
    const UpdateReport report = model->add_points(xy_.bottomRows(n - n0), z_.tail(n - n0));
    touch.path = report.path == UpdatePath::bordered ? TouchPath::bordered : TouchPath::refactorised;
    touch.refactorised_because = report.reason;
    gp_ = model;
  }
  SurfaceModelPtr surface;
  if (o.method == FitMethod::sparse && n > 0) {
    if (n > n0 || !sparse_) sparse_ = fit_sparse(h, rng, touch);
    surface = sparse_;
  } else {
    h = gp_->hyperparameters();
    touch.jitter_mm2 = gp_->factorisation().jitter_mm2;
    // An unchanged fit goes out as the same model.
    if (!exact_surface_ || exact_surface_->gp() != gp_) exact_surface_ = std::make_shared<GpSurfaceModel>(gp_, data_z_range());
    surface = exact_surface_;
  }
  touch.hyperparameters = h;
  touch.seconds = seconds_since(started);
  summary_.touches.push_back(std::move(touch));
  return surface;
}

}  // namespace touchcloud::gp
