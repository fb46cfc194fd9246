#include "touchcloud/gp/box_search.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include <ceres/first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

namespace touchcloud::gp {

namespace {

double sigmoid(double u) {
  if (u >= 0) return 1.0 / (1.0 + std::exp(-u));
  const double e = std::exp(u);
  return e / (1.0 + e);
}

// Keeps the best value seen and the first one.
struct Trace {
  BoxRun* run;
  bool first_seen = false;
  void record(const Eigen::VectorXd& x, bool ok, double value, bool with_gradient) {
    ++run->evaluations;
    if (with_gradient) ++run->gradient_evaluations;
    if (!first_seen) {
      first_seen = true;
      run->start = x;
      run->start_value = ok ? value : kNoValue;
    }
    if (!ok) {
      ++run->failed_evaluations;
      return;
    }
    if (value > run->best_value) {
      run->best_value = value;
      run->best = x;
    }
  }
};

// -f in the mapped coordinates u, x = lo + span * sigmoid(u).
class MappedNegative final : public ceres::FirstOrderFunction {
 public:
  MappedNegative(const BoxObjective& f, const Eigen::VectorXd& lo, const Eigen::VectorXd& span, Trace& trace)
      : f_(f), lo_(lo), span_(span), trace_(trace) {}

  bool Evaluate(const double* u, double* cost, double* gradient) const override {
    const Eigen::Index n = lo_.size();
    Eigen::VectorXd s(n), x(n), g = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      s[i] = sigmoid(u[i]);
      x[i] = lo_[i] + span_[i] * s[i];
    }
    double value = 0.0;
    const bool ok = f_(x, value, gradient ? &g : nullptr) && std::isfinite(value) && g.allFinite();
    trace_.record(x, ok, value, gradient != nullptr);
    if (!ok) return false;
    *cost = -value;
    if (gradient)
      for (Eigen::Index i = 0; i < n; ++i) gradient[i] = -g[i] * span_[i] * s[i] * (1.0 - s[i]);
    return true;
  }
  int NumParameters() const override { return static_cast<int>(lo_.size()); }

 private:
  const BoxObjective& f_;
  Eigen::VectorXd lo_, span_;
  Trace& trace_;
};

}  // namespace

BoxRun lbfgs_in_box(const BoxObjective& f, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                    const Eigen::VectorXd& start, const LbfgsSettings& settings) {
  const Eigen::VectorXd span = hi - lo;
  // u for the start, kept a little inside the box so that sigmoid' is not zero.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(lo.size());
  for (Eigen::Index i = 0; i < lo.size(); ++i) {
    if (span[i] <= 0) continue;
    const double t = std::clamp((start[i] - lo[i]) / span[i], 1e-6, 1.0 - 1e-6);
    u[i] = std::log(t / (1.0 - t));
  }
  BoxRun run;
  run.best = start;
  Trace trace{&run};

  ceres::GradientProblemSolver::Options solver;
  solver.line_search_direction_type = ceres::LBFGS;
  solver.max_num_iterations = settings.max_iterations;
  solver.function_tolerance = settings.function_tolerance;
  solver.gradient_tolerance = settings.gradient_tolerance;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  ceres::GradientProblem problem(new MappedNegative(f, lo, span, trace));
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(solver, problem, u.data(), &summary);
  if (!trace.first_seen) run.start = start;
  run.iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  run.report = summary.BriefReport();
  return run;
}

BoxRun quasi_newton_in_box(const BoxObjective& f, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                           const Eigen::VectorXd& start, const Eigen::MatrixXd& hessian,
                           const QuasiNewtonSettings& settings) {
  BoxRun run;
  Trace trace{&run};
  auto evaluate = [&](const Eigen::VectorXd& x, double& value, Eigen::VectorXd* gradient) {
    const bool ok = f(x, value, gradient) && std::isfinite(value) && (!gradient || gradient->allFinite());
    trace.record(x, ok, value, gradient != nullptr);
    return ok;
  };
  Eigen::VectorXd x = start.cwiseMax(lo).cwiseMin(hi), g(x.size());
  double value = kNoValue;
  run.best = x;
  if (!evaluate(x, value, &g)) {
    run.report = "quasi-Newton: the start could not be evaluated";
    return run;
  }
  Eigen::MatrixXd b = hessian;  // approximates -Hessian of f
  const char* stop = "iteration limit";
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    // Newton step in the coordinates not held at a bound by the gradient (a
    // projected Newton method: a plain clamp of the full step can stall on a face).
    std::vector<Eigen::Index> free;
    for (Eigen::Index i = 0; i < x.size(); ++i)
      if (!((x[i] <= lo[i] && g[i] < 0) || (x[i] >= hi[i] && g[i] > 0))) free.push_back(i);
    Eigen::VectorXd direction = Eigen::VectorXd::Zero(x.size());
    if (!free.empty()) {
      const Eigen::Index k = static_cast<Eigen::Index>(free.size());
      Eigen::MatrixXd b_free(k, k);
      Eigen::VectorXd g_free(k);
      for (Eigen::Index i = 0; i < k; ++i) {
        g_free[i] = g[free[i]];
        for (Eigen::Index j = 0; j < k; ++j) b_free(i, j) = b(free[i], free[j]);
      }
      const Eigen::VectorXd d = b_free.ldlt().solve(g_free);
      for (Eigen::Index i = 0; i < k; ++i) direction[free[i]] = d[i];
    }
    Eigen::VectorXd step = (x + direction).cwiseMax(lo).cwiseMin(hi) - x;
    // A step cut by the box is no Newton step: go only as far along it as the
    // model rises (else a long cut step can look like no gain at all).
    const double along = step.dot(b * step);
    if (along > 0 && g.dot(step) < along) step *= g.dot(step) / along;
    const Eigen::VectorXd target = x + step;
    const double slope = g.dot(step);
    const double gain = slope - 0.5 * step.dot(b * step);  // what the model promises
    const double scale = std::max(1.0, std::abs(value));
    if (!(slope > 0) || !(gain > settings.stop_gain * scale)) {
      stop = "converged";
      run.converged = true;
      break;
    }
    // The full step first, on a value alone.
    double t = 1.0, trial = kNoValue;
    bool accepted = evaluate(x + step, trial, nullptr) && trial > value + 1e-4 * slope;
    const double agreement = (trial - value) / gain;  // 1 where the model is exact along the step
    if (accepted && gain <= settings.final_gain * scale) {
      // Along the step, the model misses the maximum by gain (1 - agreement)^2
      // (exact for a quadratic in one variable): stop where that is nothing,
      // else take the gradient here (the trial's factorisation is reused).
      if (gain * (1.0 - agreement) * (1.0 - agreement) <= settings.stop_gain * scale) {
        x = target;
        value = trial;
        stop = "converged (last step on a value)";
        run.converged = true;
        break;
      }
    } else if (accepted && std::abs(agreement - 1.0) > 0.2 && value + slope - trial > 0) {
      // Far from quadratic (a subset's distance from the optimum): one more
      // value at the maximum of the parabola through f(x), the slope and
      // f(x + step) usually lands where a second Newton step would.
      double t_max = 4.0;  // longest step that stays in the box
      for (Eigen::Index i = 0; i < x.size(); ++i) {
        if (step[i] > 0) t_max = std::min(t_max, (hi[i] - x[i]) / step[i]);
        if (step[i] < 0) t_max = std::min(t_max, (lo[i] - x[i]) / step[i]);
      }
      const double t_parabola = std::clamp(slope / (2.0 * (value + slope - trial)), 0.2, std::max(0.2, t_max));
      double other = kNoValue;
      if (std::abs(t_parabola - 1.0) > 0.05 && evaluate(x + t_parabola * step, other, nullptr) && other > trial) {
        t = t_parabola;
        trial = other;
      }
    }
    // A failed Armijo test backtracks by the same interpolation.
    for (int halving = 0; !accepted && halving < 6; ++halving) {
      const double c = value + t * slope - trial;  // parabola f(x) + tau slope - (c / t^2) tau^2 through the trial
      t = (std::isfinite(trial) && c > 0) ? std::clamp(slope * t * t / (2.0 * c), 0.1 * t, 0.5 * t) : 0.5 * t;
      accepted = evaluate(x + t * step, trial, nullptr) && trial > value + 1e-4 * t * slope;
    }
    if (!accepted) {
      stop = "no ascent along the Newton direction";
      break;
    }
    const Eigen::VectorXd next = x + t * step;
    Eigen::VectorXd g_next(x.size());
    double next_value = 0.0;
    if (!evaluate(next, next_value, &g_next)) {  // reuses the last trial's factorisation unless t went back
      stop = "gradient failed";
      break;
    }
    const Eigen::VectorXd s = next - x, y = g - g_next;  // y: change of the gradient of -f
    if (s.dot(y) > 1e-12 * s.norm() * y.norm()) {
      const Eigen::VectorXd bs = b * s;
      b += y * y.transpose() / y.dot(s) - bs * bs.transpose() / s.dot(bs);
    }
    x = next;
    value = next_value;
    g = g_next;
    ++run.iterations;
  }
  run.hessian = b;
  run.report = std::string("quasi-Newton: ") + stop;
  return run;
}

}  // namespace touchcloud::gp
