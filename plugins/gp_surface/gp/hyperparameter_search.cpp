#include "gp/hyperparameter_search.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include <Eigen/Eigenvalues>

#include <ceres/first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

#include "gp/marginal_likelihood.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {

namespace {

double sigmoid(double u) {
  if (u >= 0) return 1.0 / (1.0 + std::exp(-u));
  const double e = std::exp(u);
  return e / (1.0 + e);
}

// What one start saw: its first evaluation and the best one.
struct StartTrace {
  int evaluations = 0, failed = 0;
  bool first_seen = false;
  double first_lml = kNoLml;
  double best_lml = kNoLml;
  LogHyperparameters best_theta = LogHyperparameters::Zero();
};

// -LML in the mapped coordinates u, theta = lo + span * sigmoid(u).
class BoundedNegativeLml final : public ceres::FirstOrderFunction {
 public:
  BoundedNegativeLml(const LmlFunction& f, const Eigen::Vector3d& lo, const Eigen::Vector3d& span, StartTrace& trace)
      : f_(f), lo_(lo), span_(span), trace_(trace) {}

  bool Evaluate(const double* u, double* cost, double* gradient) const override {
    ++trace_.evaluations;
    Eigen::Vector3d s, theta;
    for (int i = 0; i < 3; ++i) {
      s[i] = sigmoid(u[i]);
      theta[i] = lo_[i] + span_[i] * s[i];
    }
    double lml = 0.0;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    const bool ok = f_(theta, lml, gradient ? &g : nullptr) && std::isfinite(lml) && g.allFinite();
    if (!trace_.first_seen) {
      trace_.first_seen = true;
      trace_.first_lml = ok ? lml : kNoLml;
    }
    if (!ok) {
      ++trace_.failed;
      return false;
    }
    if (lml > trace_.best_lml) {
      trace_.best_lml = lml;
      trace_.best_theta = theta;
    }
    *cost = -lml;
    if (gradient)
      for (int i = 0; i < 3; ++i) gradient[i] = -g[i] * span_[i] * s[i] * (1.0 - s[i]);
    return true;
  }
  int NumParameters() const override { return 3; }

 private:
  const LmlFunction& f_;
  Eigen::Vector3d lo_, span_;
  StartTrace& trace_;
};

// u for a start theta, kept a little inside the box so sigmoid' is not zero.
Eigen::Vector3d to_mapped(const LogHyperparameters& theta, const Eigen::Vector3d& lo, const Eigen::Vector3d& span) {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (span[i] <= 0) continue;
    const double f = std::clamp((theta[i] - lo[i]) / span[i], 1e-6, 1.0 - 1e-6);
    u[i] = std::log(f / (1.0 - f));
  }
  return u;
}

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
  for (double l : start_lengthscales_mm)
    if (!(l > 0) || !std::isfinite(l)) fail("start lengthscale " + std::to_string(l) + " mm must be finite and > 0");
}

SearchResult maximise_lml(const LmlFunction& f, const HyperparameterBounds& bounds,
                          const std::vector<Hyperparameters>& starts, const SearchOptions& options) {
  options.validate();
  if (starts.empty()) throw InputError("GP hyperparameter search: no start points");
  const LogHyperparameters lo = to_log(bounds.lower), hi = to_log(bounds.upper);
  if (!lo.allFinite() || !hi.allFinite() || !(hi.array() >= lo.array()).all())
    throw InputError("GP hyperparameter search: bounds must be finite, positive and lower <= upper");
  const Eigen::Vector3d span = hi - lo;

  ceres::GradientProblemSolver::Options solver;
  solver.line_search_direction_type = ceres::LBFGS;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.gradient_tolerance = options.gradient_tolerance;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;

  SearchResult result;
  result.bounds = bounds;
  for (const Hyperparameters& start : starts) {
    StartTrace trace;
    ceres::GradientProblem problem(new BoundedNegativeLml(f, lo, span, trace));
    const Eigen::Vector3d u = to_mapped(to_log(start), lo, span);
    Eigen::Vector3d u_final = u;
    ceres::GradientProblemSolver::Summary summary;
    ceres::Solve(solver, problem, u_final.data(), &summary);

    StartReport report;
    report.start = from_log(lo + span.cwiseProduct(u.unaryExpr(&sigmoid)));  // as evaluated
    report.start_lml = trace.first_lml;
    report.lml = trace.best_lml;
    report.result = trace.best_lml > kNoLml ? from_log(trace.best_theta) : start;
    report.iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
    report.evaluations = trace.evaluations;
    report.failed_evaluations = trace.failed;
    report.solver_report = summary.BriefReport();
    result.iterations += report.iterations;
    result.evaluations += report.evaluations;
    result.failed_evaluations += report.failed_evaluations;
    if (report.lml > result.lml) {
      result.lml = report.lml;
      result.hyperparameters = report.result;
      result.best_start = result.starts.size();
    }
    result.starts.push_back(std::move(report));
  }
  result.initial_lml = result.starts.front().start_lml;
  if (!(result.lml > kNoLml)) {
    std::ostringstream msg;
    msg << "GP hyperparameter search: the likelihood could not be evaluated at any point from " << starts.size()
        << " starts";
    throw RunError(msg.str());
  }
  return result;
}

namespace {

// Wraps the exact likelihood as an LmlFunction; keeps the last failure's text.
LmlFunction exact_lml(MarginalLikelihood& likelihood, std::string& last_failure) {
  return [&likelihood, &last_failure](const LogHyperparameters& theta, double& lml, Eigen::Vector3d* gradient) {
    try {
      const LmlEvaluation e = likelihood.evaluate(from_log(theta), gradient != nullptr);
      lml = e.lml;
      if (gradient) *gradient = e.gradient;
      return true;
    } catch (const RunError& error) {
      last_failure = error.what();
      return false;
    }
  };
}

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

// Polish of a subset optimum on the full data: quasi-Newton steps in log
// space whose first Hessian is the subset's (finite differences of its
// analytic gradient, 1/8 of a full evaluation each at half the data), scaled
// by n / subset size, as the LML is a sum over points; BFGS updates it from
// the full-data gradients. Near the optimum a step or three suffice where
// L-BFGS, which starts from the identity, takes about ten. A step is kept
// only when the LML rises (Armijo, halving up to 6 times), so the result is
// never worse than the start. Returns a result with no starts when the
// subset Hessian is not negative definite or the start cannot be evaluated;
// the caller then runs L-BFGS.
SearchResult newton_polish(const LmlFunction& f, const LmlFunction& f_subset, double scale, const Hyperparameters& start,
                           double start_lml, const HyperparameterBounds& bounds, const SearchOptions& options) {
  SearchResult result;
  result.bounds = bounds;
  const LogHyperparameters lo = to_log(bounds.lower), hi = to_log(bounds.upper);
  auto clamp_log = [&](LogHyperparameters t) { return LogHyperparameters(t.cwiseMax(lo).cwiseMin(hi)); };
  LogHyperparameters theta = clamp_log(to_log(start));

  // Hessian of -LML on the subset, scaled to the full data.
  constexpr double kStep = 1e-4;
  double value = 0;
  Eigen::Vector3d g0, gi;
  if (!f_subset(theta, value, &g0)) return result;
  Eigen::Matrix3d b;  // approximates the Hessian of -LML
  for (int i = 0; i < 3; ++i) {
    LogHyperparameters t = theta;
    t[i] += kStep;
    if (!f_subset(t, value, &gi)) return result;
    b.col(i) = -(gi - g0) / kStep * scale;
  }
  b = 0.5 * (b + b.transpose()).eval();
  if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(b).eigenvalues().minCoeff() <= 0) return result;

  StartReport report;
  report.start = from_log(theta);
  double lml = kNoLml;
  Eigen::Vector3d g;
  ++report.evaluations;
  if (!f(theta, lml, &g)) return result;  // reuses the factor of the candidate evaluation
  report.start_lml = lml;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    const Eigen::Vector3d direction = b.ldlt().solve(g);  // ascent: B d = grad LML
    const LogHyperparameters target = clamp_log(theta + direction);
    const Eigen::Vector3d step = target - theta;
    const double predicted = g.dot(step);
    if (!(predicted > options.function_tolerance * std::max(1.0, std::abs(lml)))) break;
    double t = 1.0, trial_lml = kNoLml;
    bool accepted = false;
    for (int halving = 0; halving <= 6; ++halving, t *= 0.5) {
      ++report.evaluations;
      if (f(theta + t * step, trial_lml, nullptr) && trial_lml > lml + 1e-4 * t * predicted) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    const LogHyperparameters next = theta + t * step;  // inside the box: both ends are
    Eigen::Vector3d g_next;
    ++report.evaluations;
    double next_lml = 0;
    if (!f(next, next_lml, &g_next)) break;  // the factor from the accepted trial is reused
    const Eigen::Vector3d s_vec = next - theta, y = -(g_next - g);  // of -LML
    if (s_vec.dot(y) > 1e-12 * s_vec.norm() * y.norm()) {
      const Eigen::Vector3d bs = b * s_vec;
      b += y * y.transpose() / y.dot(s_vec) - bs * bs.transpose() / s_vec.dot(bs);
    }
    theta = next;
    lml = next_lml;
    g = g_next;
    ++report.iterations;
  }
  report.lml = lml;
  report.result = from_log(theta);
  if (!(lml >= start_lml)) {  // cannot happen with exact arithmetic; keep the contract regardless
    report.lml = start_lml;
    report.result = start;
  }
  report.solver_report = "quasi-Newton polish from the subset Hessian";
  result.hyperparameters = report.result;
  result.lml = report.lml;
  result.iterations = report.iterations;
  result.evaluations = report.evaluations;
  result.starts.push_back(std::move(report));
  return result;
}

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
  std::vector<Hyperparameters> starts = start_points(options, scales, bounds);

  MarginalLikelihood likelihood(options.kernel, xy_mm, z_mm, options.jitter);
  std::string last_failure;
  const LmlFunction f = exact_lml(likelihood, last_failure);
  auto rethrow = [&](const RunError& error) {
    throw RunError(std::string(error.what()) + (last_failure.empty() ? "" : ": " + last_failure));
  };

  const bool screen = options.screening_points > 0 && n > options.screening_points;
  if (!screen) {
    try {
      return maximise_lml(f, bounds, starts, options);
    } catch (const RunError& error) {
      rethrow(error);
    }
  }

  // Restarts on every (n / m)-th point, then one full-data run from the best
  // of the starts and the subset optima, judged by the full-data LML.
  const Eigen::Index m = options.screening_points;
  auto strided = [&](Eigen::Index size) {
    std::pair<Eigen::MatrixX2d, Eigen::VectorXd> sub{Eigen::MatrixX2d(size, 2), Eigen::VectorXd(size)};
    for (Eigen::Index i = 0; i < size; ++i) {
      const Eigen::Index k = i * n / size;
      sub.first.row(i) = xy_mm.row(k);
      sub.second[i] = z_mm[k];
    }
    return sub;
  };
  std::vector<StartReport> screening;
  try {
    const auto [sub_xy, sub_z] = strided(m);
    MarginalLikelihood sub_likelihood(options.kernel, sub_xy, sub_z, options.jitter);
    std::string sub_failure;
    screening = maximise_lml(exact_lml(sub_likelihood, sub_failure), bounds, starts, options).starts;
  } catch (const RunError&) {
    // The subset could not be evaluated anywhere: fall through to the starts.
  }

  // Coarse to fine: the best subset optimum is refined on subsets twice as
  // large while they hold at most half the data. Where the surface has
  // detail the optimum moves with point density (a sparse subset reads fine
  // relief as noise), and the full-data run, at 8x the cost of a half-size
  // one, then starts close to its own optimum.
  std::vector<Hyperparameters> refined;
  Eigen::Index refined_level = m;  // subset size the best subset point was optimised on
  const auto best_subset = std::max_element(screening.begin(), screening.end(),
                                            [](const StartReport& a, const StartReport& b) { return a.lml < b.lml; });
  if (best_subset != screening.end() && best_subset->lml > kNoLml) {
    Hyperparameters h = best_subset->result;
    for (Eigen::Index level = 2 * m; 2 * level <= n; level *= 2) {
      try {
        const auto [level_xy, level_z] = strided(level);
        MarginalLikelihood level_likelihood(options.kernel, level_xy, level_z, options.jitter);
        std::string level_failure;
        h = maximise_lml(exact_lml(level_likelihood, level_failure), bounds, {h}, options).hyperparameters;
        refined = {h};
        refined_level = level;
      } catch (const RunError&) {
        break;  // keep the last level that could be evaluated
      }
    }
  }

  // Full-data values at the first start (the reference a search must not
  // fall below) and at the refined optimum, or else at each distinct subset
  // optimum; each evaluation costs a factorisation.
  std::vector<Hyperparameters> candidates{screening.empty() ? starts.front() : screening.front().start};
  if (!refined.empty()) {
    candidates.push_back(refined.front());
  } else {
    for (const StartReport& s : screening)
      if (s.lml > kNoLml && std::none_of(candidates.begin() + 1, candidates.end(), [&](const Hyperparameters& c) {
            return ((to_log(c) - to_log(s.result)).cwiseAbs().array() < 1e-6).all();  // the same optimum
          }))
        candidates.push_back(s.result);
  }
  if (candidates.size() == 1)
    for (std::size_t i = 1; i < starts.size(); ++i) candidates.push_back(starts[i]);
  double initial_lml = kNoLml, best_lml = kNoLml;
  Hyperparameters best = starts.front();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    double value = kNoLml;
    if (!f(to_log(candidates[i]), value, nullptr)) value = kNoLml;
    if (i == 0) initial_lml = value;
    if (value > best_lml) {
      best_lml = value;
      best = candidates[i];
    }
  }
  SearchResult result;
  const bool from_subset_optimum = !screening.empty() && !(best == candidates.front());
  if (from_subset_optimum) {
    const auto [level_xy, level_z] = strided(std::min(refined_level, n));
    MarginalLikelihood level_likelihood(options.kernel, level_xy, level_z, options.jitter);
    std::string level_failure;
    result = newton_polish(f, exact_lml(level_likelihood, level_failure),
                           static_cast<double>(n) / static_cast<double>(level_xy.rows()), best, best_lml, bounds,
                           options);
  }
  if (result.starts.empty()) {  // no subset optimum to polish, or its Hessian was unusable
    try {
      result = maximise_lml(f, bounds, {best}, options);
    } catch (const RunError& error) {
      rethrow(error);
    }
  }
  result.initial_lml = initial_lml;
  result.screening_points = m;
  result.screening = std::move(screening);
  return result;
}

}  // namespace touchcloud::gp
