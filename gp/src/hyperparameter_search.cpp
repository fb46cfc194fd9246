#include "touchcloud/gp/hyperparameter_search.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "touchcloud/gp/marginal_likelihood.hpp"
#include "touchcloud/gp/point_subset.hpp"
#include "touchcloud/error.hpp"
#include <ceres/version.h>
#include "touchcloud/library_versions.hpp"

namespace touchcloud::gp {

// Recorded in summary.json's versions when this library is loaded.
namespace {
const LibraryVersion ceres_version("ceres", CERES_VERSION_STRING);
}  // namespace

void SearchOptions::validate() const {
  auto fail = [](const std::string& what) { throw InputError("GP hyperparameter search: " + what); };
  bounds.validate();
  jitter.validate();
  if (min_points < 2) fail("min_points = " + std::to_string(min_points) + " must be >= 2");
  if (screening_points != 0 && screening_points < min_points)
    fail("screening_points = " + std::to_string(screening_points) + " must be 0 (off) or >= min_points");
  if (max_iterations < 1) fail("max_iterations = " + std::to_string(max_iterations) + " must be >= 1");
  if (!(function_tolerance > 0)) fail("function_tolerance must be > 0");
  if (!(gradient_tolerance > 0)) fail("gradient_tolerance must be > 0");
  if (!(stop_gain > 0) || !(stop_gain < 1e-2)) fail("stop_gain must be in (0, 0.01)");
  for (double l : start_lengthscales_mm)
    if (!(l > 0) || !std::isfinite(l)) fail("start lengthscale " + std::to_string(l) + " mm must be finite and > 0");
}

namespace {

LbfgsSettings lbfgs_settings(const SearchOptions& options) {
  return {options.max_iterations, options.function_tolerance, options.gradient_tolerance};
}

StartReport report_of(const BoxRun& run, const std::function<Hyperparameters(const Eigen::VectorXd&)>& at) {
  StartReport r;
  r.start = at(run.start);
  r.start_lml = run.start_value;
  r.lml = run.best_value;
  r.result = at(run.best);
  r.iterations = run.iterations;
  r.evaluations = run.evaluations;
  r.gradient_evaluations = run.gradient_evaluations;
  r.failed_evaluations = run.failed_evaluations;
  r.solver_report = run.report;
  return r;
}

void add_run(SearchResult& result, StartReport report) {
  result.iterations += report.iterations;
  result.evaluations += report.evaluations;
  result.gradient_evaluations += report.gradient_evaluations;
  result.failed_evaluations += report.failed_evaluations;
  if (report.lml > result.lml) {
    result.lml = report.lml;
    result.hyperparameters = report.result;
    result.best_start = result.starts.size();
  }
  result.starts.push_back(std::move(report));
}

// L-BFGS from each start: every run's report, and the best point reached
// (empty, at kNoLml, when none could be evaluated).
struct Restarts {
  std::vector<StartReport> reports;
  Eigen::VectorXd best;
  double best_value = kNoLml;
};
Restarts lbfgs_restarts(const BoxObjective& f, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                        const std::vector<Eigen::VectorXd>& starts, const LbfgsSettings& lbfgs,
                        const std::function<Hyperparameters(const Eigen::VectorXd&)>& at) {
  Restarts out;
  for (const Eigen::VectorXd& start : starts) {
    const BoxRun run = lbfgs_in_box(f, lo, hi, start, lbfgs);
    out.reports.push_back(report_of(run, at));
    if (run.best_value > out.best_value) {
      out.best_value = run.best_value;
      out.best = run.best;
    }
  }
  return out;
}

// The restarts as the search's own runs: the best becomes the result.
void add_restarts(SearchResult& result, Restarts restarts) {
  for (StartReport& report : restarts.reports) add_run(result, std::move(report));
  result.initial_lml = result.starts.front().start_lml;
}

}  // namespace

SearchResult maximise_lml(const LmlFunction& f, const HyperparameterBounds& bounds,
                          const std::vector<Hyperparameters>& starts, const SearchOptions& options) {
  options.validate();
  if (starts.empty()) throw InputError("GP hyperparameter search: no start points");
  const LogHyperparameters lo = to_log(bounds.lower), hi = to_log(bounds.upper);
  if (!lo.allFinite() || !hi.allFinite() || !(hi.array() >= lo.array()).all())
    throw InputError("GP hyperparameter search: bounds must be finite, positive and lower <= upper");
  const BoxObjective objective = [&f](const Eigen::VectorXd& x, double& value, Eigen::VectorXd* gradient) {
    Eigen::Vector3d g;
    if (!f(x, value, gradient ? &g : nullptr)) return false;
    if (gradient) *gradient = g;
    return true;
  };
  std::vector<Eigen::VectorXd> from;
  for (const Hyperparameters& start : starts) from.push_back(to_log(start));
  SearchResult result;
  result.bounds = bounds;
  add_restarts(result, lbfgs_restarts(objective, lo, hi, from, lbfgs_settings(options),
                                      [](const Eigen::VectorXd& x) { return from_log(x); }));
  if (!(result.lml > kNoLml)) {
    std::ostringstream msg;
    msg << "GP hyperparameter search: the likelihood could not be evaluated at any point from " << starts.size()
        << " starts";
    throw RunError(msg.str());
  }
  return result;
}

namespace {

Hyperparameters clamp_into(const Hyperparameters& h, const HyperparameterBounds& b) {
  return {std::clamp(h.signal_variance_mm2, b.lower.signal_variance_mm2, b.upper.signal_variance_mm2),
          std::clamp(h.lengthscale_mm, b.lower.lengthscale_mm, b.upper.lengthscale_mm),
          std::clamp(h.noise_variance_mm2, b.lower.noise_variance_mm2, b.upper.noise_variance_mm2)};
}

std::vector<Hyperparameters> start_points(const SearchOptions& options, const DataScales& scales,
                                          const HyperparameterBounds& bounds) {
  std::vector<Hyperparameters> starts;
  for (const Hyperparameters& h : options.start_hyperparameters) {
    h.validate("GP hyperparameter search start");
    starts.push_back(clamp_into(h, bounds));
  }
  if (!starts.empty()) return starts;
  std::vector<double> lengthscales = options.start_lengthscales_mm;
  if (lengthscales.empty()) {
    const double a = 3.0 * scales.spacing_mm, b = std::max(a, scales.extent_mm);
    lengthscales = {a, std::sqrt(a * b), b};
  }
  for (double l : lengthscales)
    starts.push_back(clamp_into({scales.z_variance_mm2, l, 1e-2 * scales.z_variance_mm2}, bounds));
  return starts;
}

// The profiled search space: x = (log lengthscale, log g), g = noise / s2,
// with g's range wide enough for every (s2, noise) in the bounds.
struct ProfileBox {
  Eigen::Vector2d lo, hi;
  explicit ProfileBox(const HyperparameterBounds& b)
      : lo(std::log(b.lower.lengthscale_mm), std::log(b.lower.noise_variance_mm2 / b.upper.signal_variance_mm2)),
        hi(std::log(b.upper.lengthscale_mm), std::log(b.upper.noise_variance_mm2 / b.lower.signal_variance_mm2)) {}
  Eigen::VectorXd of(const Hyperparameters& h) const {
    const Eigen::Vector2d x(std::log(h.lengthscale_mm), std::log(h.noise_variance_mm2 / h.signal_variance_mm2));
    return x.cwiseMax(lo).cwiseMin(hi);
  }
};

// The profiled LML of one data set as a BoxObjective; keeps the last failure's
// text and the hyperparameters (s2 at its best) of each point evaluated.
class Profile {
 public:
  Profile(KernelKind kind, const Eigen::MatrixX2d& xy, const Eigen::VectorXd& z, const HyperparameterBounds& bounds,
          const JitterSchedule& jitter, PriorMean level)
      : likelihood_(kind, xy, z, jitter, level), bounds_(bounds) {}

  BoxObjective objective() {
    return [this](const Eigen::VectorXd& x, double& value, Eigen::VectorXd* gradient) {
      try {
        const ProfiledEvaluation e =
            likelihood_.evaluate_profiled(std::exp(x[0]), std::exp(x[1]), bounds_, gradient != nullptr);
        value = e.lml;
        if (gradient) *gradient = e.gradient;
        seen_.emplace_back(x, e.hyperparameters);
        return true;
      } catch (const RunError& error) {
        last_failure = error.what();
        return false;
      }
    };
  }
  // The hyperparameters at a point: as evaluated, or (l, g) with s2 = 1 for a
  // point that could not be.
  Hyperparameters at(const Eigen::VectorXd& x) const {
    for (const auto& [point, h] : seen_)
      if (point == x) return h;
    return {1.0, std::exp(x[0]), std::exp(x[1])};
  }
  std::string last_failure;

 private:
  MarginalLikelihood likelihood_;
  HyperparameterBounds bounds_;
  std::vector<std::pair<Eigen::VectorXd, Hyperparameters>> seen_;
};

// -Hessian of the profile at x by forward differences of its gradient, or an
// empty matrix when it is not positive definite there (or cannot be evaluated).
Eigen::MatrixXd negative_hessian(const BoxObjective& f, const Eigen::VectorXd& x) {
  constexpr double kStep = 1e-4;
  double value = 0;
  Eigen::VectorXd g0, gi;
  if (!f(x, value, &g0)) return {};
  Eigen::MatrixXd b(x.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xi = x;
    xi[i] += kStep;
    if (!f(xi, value, &gi)) return {};
    b.col(i) = -(gi - g0) / kStep;
  }
  b = 0.5 * (b + b.transpose()).eval();
  if (!(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(b).eigenvalues().minCoeff() > 0)) return {};
  return b;
}

// Subsets keep 16 runs of consecutive points (parts of touches).
constexpr Eigen::Index kSubsetRuns = 16;

// A coarse level only seeds the next, whose optimum lies ~0.1 away in log
// space: it stops once a step would gain less than this (relative).
constexpr double kCoarseStopGain = 1e-5;

}  // namespace

SearchResult select_hyperparameters(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm,
                                    const SearchOptions& options) {
  options.validate();
  const Eigen::Index n = xy_mm.rows();
  if (n < options.min_points) {
    std::ostringstream msg;
    msg << "GP hyperparameter selection needs at least " << options.min_points << " training points, got " << n;
    throw InputError(msg.str());
  }
  const DataScales scales = data_scales(xy_mm, z_mm);
  const HyperparameterBounds bounds = bounds_from_scales(scales, options.bounds);
  const std::vector<Hyperparameters> starts = start_points(options, scales, bounds);
  const ProfileBox box(bounds);
  const LbfgsSettings lbfgs = lbfgs_settings(options);

  Profile full(options.kernel, xy_mm, z_mm, bounds, options.jitter, options.prior_mean);
  const BoxObjective f = full.objective();
  const auto at_full = [&full](const Eigen::VectorXd& x) { return full.at(x); };
  auto fail = [&](const std::string& what) {
    throw RunError("GP hyperparameter search: " + what + (full.last_failure.empty() ? "" : ": " + full.last_failure));
  };

  SearchResult result;
  result.bounds = bounds;
  QuasiNewtonSettings polish;
  polish.max_iterations = options.max_iterations;
  polish.stop_gain = options.stop_gain;
  polish.final_gain = std::max(polish.final_gain, 100.0 * options.stop_gain);
  auto finish = [&](const BoxRun& run) {
    add_run(result, report_of(run, at_full));
    if (run.hessian.size() > 0) result.hessian_per_point = run.hessian / static_cast<double>(n);
    if (!(result.lml > kNoLml)) fail("the likelihood could not be evaluated on all " + std::to_string(n) + " points");
    return result;
  };

  // A warm start with its curvature: straight to quasi-Newton steps on all
  // the points.
  const Eigen::Matrix2d& curvature = options.start_hessian_per_point;
  if (starts.size() == 1 && curvature.allFinite() && curvature(0, 0) > 0 && curvature.determinant() > 0) {
    BoxRun run = quasi_newton_in_box(f, box.lo, box.hi, box.of(starts.front()), curvature * static_cast<double>(n),
                                     polish);
    if (run.best_value > kNoLml) {
      const double initial = run.start_value;
      // A stale curvature that leads nowhere: L-BFGS takes over from the best point.
      if (!run.converged) run = lbfgs_in_box(f, box.lo, box.hi, run.best, lbfgs);
      result.initial_lml = initial;
      return finish(run);
    }
  }

  std::vector<Eigen::VectorXd> start_points_in_box;
  for (const Hyperparameters& start : starts) start_points_in_box.push_back(box.of(start));
  const bool screen = options.screening_points > 0 && n > options.screening_points;
  if (!screen) {
    Restarts restarts = lbfgs_restarts(f, box.lo, box.hi, start_points_in_box, lbfgs, at_full);
    const Eigen::VectorXd best = restarts.best;
    add_restarts(result, std::move(restarts));
    if (!(result.lml > kNoLml))
      fail("the likelihood could not be evaluated at any point from " + std::to_string(starts.size()) + " starts");
    // The curvature for a later warm start (two gradients at most
    // `screening_points` points: cheap next to a search).
    const Eigen::MatrixXd curvature_here = negative_hessian(f, best);
    if (curvature_here.size() > 0) result.hessian_per_point = curvature_here / static_cast<double>(n);
    return result;
  }

  // Restarts on a subset; the best climbs to larger subsets.
  const Eigen::Index m = options.screening_points;
  result.screening_points = m;
  Eigen::VectorXd x;         // the best point so far
  Eigen::MatrixXd hessian;   // -Hessian there, on `level` points (empty: none usable)
  Eigen::Index level = m;
  {
    const auto [sub_xy, sub_z] = subset_of_runs(xy_mm, z_mm, m, kSubsetRuns);
    Profile sub(options.kernel, sub_xy, sub_z, bounds, options.jitter, options.prior_mean);
    const BoxObjective fs = sub.objective();
    Restarts restarts =
        lbfgs_restarts(fs, box.lo, box.hi, start_points_in_box, lbfgs, [&sub](const Eigen::VectorXd& p) { return sub.at(p); });
    result.screening = std::move(restarts.reports);
    x = restarts.best;
    if (restarts.best_value > kNoLml) hessian = negative_hessian(fs, x);
  }
  for (Eigen::Index next = 2 * m; x.size() > 0 && 2 * next <= n; next *= 2) {
    const auto [sub_xy, sub_z] = subset_of_runs(xy_mm, z_mm, next, kSubsetRuns);
    Profile sub(options.kernel, sub_xy, sub_z, bounds, options.jitter, options.prior_mean);
    const BoxObjective fs = sub.objective();
    BoxRun run;
    if (hessian.size() > 0) {
      QuasiNewtonSettings coarse;
      coarse.max_iterations = options.max_iterations;
      coarse.stop_gain = coarse.final_gain = kCoarseStopGain;
      const double scale = static_cast<double>(next) / static_cast<double>(level);
      run = quasi_newton_in_box(fs, box.lo, box.hi, x, hessian * scale, coarse);
    }
    if (!(run.best_value > kNoLml)) {
      LbfgsSettings loose = lbfgs;
      loose.function_tolerance = kCoarseStopGain;
      run = lbfgs_in_box(fs, box.lo, box.hi, x, loose);
    }
    if (!(run.best_value > kNoLml)) break;  // keep the last level that could be evaluated
    result.refinement.push_back(report_of(run, [&sub](const Eigen::VectorXd& p) { return sub.at(p); }));
    x = run.best;
    hessian = run.hessian;  // empty after L-BFGS
    level = next;
  }

  // All the data: the LML at the first start (the reference a search must
  // not fall below) and at the climb's best point; the last climb starts from
  // the better one (the subset's optimum is judged on all the points: with
  // touches of fine relief it can lie farther than the first start). The
  // factorisation of the point evaluated last is reused for its gradient.
  const Eigen::VectorXd first = box.of(starts.front());
  double initial = kNoLml, at_x = kNoLml;
  if (!f(first, initial, nullptr)) initial = kNoLml;
  result.initial_lml = initial;
  if (x.size() > 0 && !f(x, at_x, nullptr)) at_x = kNoLml;
  const Eigen::VectorXd& from = at_x >= initial && at_x > kNoLml ? x : first;
  BoxRun run;
  if (hessian.size() > 0) {
    const double scale = static_cast<double>(n) / static_cast<double>(level);
    run = quasi_newton_in_box(f, box.lo, box.hi, from, hessian * scale, polish);
  }
  if (!(run.best_value > kNoLml)) {
    run = lbfgs_in_box(f, box.lo, box.hi, from, lbfgs);
  } else if (!run.converged) {
    run = lbfgs_in_box(f, box.lo, box.hi, run.best, lbfgs);
  }
  return finish(run);
}

}  // namespace touchcloud::gp
