// Hyperparameter selection: hard cases 4 (units) and 10 (optimiser), the data
// checks, and recovery of known hyperparameters.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/hyperparameter_search.hpp"
#include "touchcloud/gp/marginal_likelihood.hpp"
#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {
namespace {

using test::grid_xy;
using test::heights;
using test::random_xy;

// A sample of a GP prior with known hyperparameters (seeded).
Eigen::VectorXd prior_sample(KernelKind kind, const Hyperparameters& h, const Eigen::MatrixX2d& xy, unsigned seed) {
  const Kernel k(kind, h);
  const Eigen::Index n = xy.rows();
  Eigen::MatrixXd a(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) a(i, j) = k.covariance((xy.row(i) - xy.row(j)).squaredNorm());
  a.diagonal().array() += h.noise_variance_mm2 + 1e-9;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) w[i] = g(rng);
  return Eigen::LLT<Eigen::MatrixXd>(a).matrixL() * w;
}

TEST(GpHyperparameterSearch, RecoversKnownHyperparameters) {
  const Eigen::MatrixX2d xy = random_xy(250, 31);
  const Hyperparameters truth{4.0, 8.0, 0.01};
  const Eigen::VectorXd z = prior_sample(KernelKind::rbf, truth, xy, 32);
  const SearchResult r = select_hyperparameters(xy, z);
  EXPECT_NEAR(r.hyperparameters.lengthscale_mm / truth.lengthscale_mm, 1.0, 0.25);
  EXPECT_NEAR(r.hyperparameters.noise_variance_mm2 / truth.noise_variance_mm2, 1.0, 0.4);
  EXPECT_GT(r.hyperparameters.signal_variance_mm2, truth.signal_variance_mm2 / 4);
  EXPECT_LT(r.hyperparameters.signal_variance_mm2, truth.signal_variance_mm2 * 4);
  EXPECT_TRUE(r.bounds.contains(r.hyperparameters));
}

// The noise cap (a sensor's accuracy): data that the likelihood prefers to
// explain as 2 mm noise get at most the capped noise, and the cap is a bound.
TEST(GpHyperparameterSearch, NoiseCapBoundsTheSelectedNoise) {
  const Eigen::MatrixX2d xy = random_xy(200, 41);
  const Eigen::VectorXd z = prior_sample(KernelKind::rbf, {4.0, 1.0, 4.0}, xy, 42);
  const SearchResult free = select_hyperparameters(xy, z);
  EXPECT_GT(free.hyperparameters.noise_variance_mm2, 1.0);
  SearchOptions capped;
  capped.bounds.noise_sd_max = 0.5;
  const SearchResult r = select_hyperparameters(xy, z, capped);
  EXPECT_DOUBLE_EQ(r.bounds.upper.noise_variance_mm2, 0.25);
  EXPECT_LE(r.hyperparameters.noise_variance_mm2, 0.25);
  EXPECT_TRUE(std::isfinite(r.lml));
  capped.bounds.noise_sd_max = 0.0;
  EXPECT_THROW(select_hyperparameters(xy, z, capped), InputError);
}

// The noise floor (a sensor's repeatability): noise-free data, which the
// likelihood explains with next to no noise, get at least the floor, and the
// floor is a bound; a negative floor or one at the cap is an InputError.
TEST(GpHyperparameterSearch, NoiseFloorBoundsTheSelectedNoise) {
  const Eigen::MatrixX2d xy = random_xy(150, 43);
  const Eigen::VectorXd z = heights(xy);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    SearchOptions options;
    options.kernel = kind;
    EXPECT_LT(select_hyperparameters(xy, z, options).hyperparameters.noise_variance_mm2, 1e-3) << to_string(kind);
    options.bounds.noise_sd_min = 0.1;
    const SearchResult r = select_hyperparameters(xy, z, options);
    EXPECT_DOUBLE_EQ(r.bounds.lower.noise_variance_mm2, 0.01);
    EXPECT_GE(r.hyperparameters.noise_variance_mm2, 0.01) << to_string(kind);
    EXPECT_TRUE(std::isfinite(r.lml));
  }
  SearchOptions bad;
  bad.bounds.noise_sd_min = -0.1;
  EXPECT_THROW(select_hyperparameters(xy, z, bad), InputError);
  bad.bounds.noise_sd_min = 0.5;
  bad.bounds.noise_sd_max = 0.5;
  EXPECT_THROW(select_hyperparameters(xy, z, bad), InputError);
}

// Case 10: the result is no worse than the first start, than any start point,
// or than any start's own optimum; it is a local maximum of the LML.
TEST(GpHyperparameterSearch, NeverWorseThanAnyStartOrRestart) {
  const Eigen::MatrixX2d xy = random_xy(150, 33);
  const Eigen::VectorXd z = heights(xy, 0.1);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    SearchOptions options;
    options.kernel = kind;
    options.start_lengthscales_mm = {1.0, 10.0, 300.0};
    const SearchResult r = select_hyperparameters(xy, z, options);
    ASSERT_EQ(r.starts.size(), 3u);
    EXPECT_GT(r.iterations, 0);
    EXPECT_GE(r.lml, r.initial_lml);
    EXPECT_EQ(r.initial_lml, r.starts[0].start_lml);
    for (const StartReport& s : r.starts) {
      EXPECT_GE(s.lml, s.start_lml) << s.solver_report;
      EXPECT_GE(r.lml, s.lml);
    }
    EXPECT_EQ(r.lml, r.starts[r.best_start].lml);

    MarginalLikelihood lml(kind, xy, z);
    EXPECT_NEAR(lml.evaluate(r.hyperparameters, false).lml, r.lml, 1e-9 * std::abs(r.lml));
    for (const StartReport& s : r.starts)
      EXPECT_NEAR(lml.evaluate(s.start, false).lml, s.start_lml, 1e-9 * std::abs(s.start_lml));
    for (int i = 0; i < 3; ++i)
      for (double d : {-0.05, 0.05}) {
        LogHyperparameters t = to_log(r.hyperparameters);
        t[i] += d;
        EXPECT_LE(lml.evaluate(from_log(t), false).lml, r.lml + 1e-9) << to_string(kind) << " parameter " << i;
      }
  }
}

// Case 10 with screening: restarts on a subset, a climb to all the data;
// the result beats the first start (evaluated on all the data, s2 at its
// best) and every subset optimum on the full-data LML, and is a local
// maximum there.
TEST(GpHyperparameterSearch, ScreeningOnASubsetNeverLosesToACandidate) {
  const Eigen::MatrixX2d xy = random_xy(400, 42);
  const Eigen::VectorXd z = heights(xy, 0.1);
  SearchOptions options;
  options.screening_points = 100;
  options.start_hyperparameters = {{1.0, 2.0, 0.05}, {1.0, 10.0, 0.05}, {1.0, 40.0, 0.05}};
  const SearchResult r = select_hyperparameters(xy, z, options);
  EXPECT_EQ(r.screening_points, 100);
  ASSERT_EQ(r.screening.size(), 3u);
  ASSERT_EQ(r.refinement.size(), 1u);  // 200 points, then all 400
  ASSERT_EQ(r.starts.size(), 1u);
  MarginalLikelihood lml(KernelKind::rbf, xy, z);
  EXPECT_NEAR(r.initial_lml, lml.evaluate_profiled(2.0, 0.05, r.bounds, false).lml, 1e-10 * std::abs(r.initial_lml));
  EXPECT_GE(r.initial_lml, lml.evaluate(options.start_hyperparameters[0], false).lml);
  EXPECT_GE(r.lml, r.initial_lml);
  EXPECT_NEAR(lml.evaluate(r.hyperparameters, false).lml, r.lml, 1e-10 * std::abs(r.lml));
  for (const StartReport& s : r.screening) {
    EXPECT_GE(r.lml, lml.evaluate(s.start, false).lml);
    EXPECT_GE(r.lml, lml.evaluate(s.result, false).lml);
  }
  for (int i = 0; i < 3; ++i)
    for (double d : {-0.05, 0.05}) {
      LogHyperparameters t = to_log(r.hyperparameters);
      t[i] += d;
      EXPECT_LE(lml.evaluate(from_log(t), false).lml, r.lml + 1e-9) << "parameter " << i;
    }
}

// The climb through subsets ends at the full-data optimum itself, not near
// it: the same LML as an L-BFGS search on all the points from the same start,
// to far below what any hyperparameter difference would show, with a
// vanishing gradient.
TEST(GpHyperparameterSearch, ScreeningReachesTheFullDataOptimum) {
  const Eigen::MatrixX2d xy = random_xy(600, 44);
  const Eigen::VectorXd z = heights(xy, 0.05);
  SearchOptions screened;
  screened.screening_points = 140;  // levels 140, 280, then 600
  screened.start_hyperparameters = {{1.0, 10.0, 0.01}};
  SearchOptions direct = screened;
  direct.screening_points = 0;
  const SearchResult a = select_hyperparameters(xy, z, screened);
  const SearchResult b = select_hyperparameters(xy, z, direct);
  ASSERT_EQ(a.refinement.size(), 1u);
  EXPECT_GE(a.lml, b.lml - 1e-8);
  EXPECT_NEAR(a.hyperparameters.lengthscale_mm / b.hyperparameters.lengthscale_mm, 1.0, 1e-4);
  EXPECT_NEAR(a.hyperparameters.noise_variance_mm2 / b.hyperparameters.noise_variance_mm2, 1.0, 1e-3);
  MarginalLikelihood lml(KernelKind::rbf, xy, z);
  const Hyperparameters& h = a.hyperparameters;
  const ProfiledEvaluation at =
      lml.evaluate_profiled(h.lengthscale_mm, h.noise_variance_mm2 / h.signal_variance_mm2, a.bounds, true);
  EXPECT_LT(at.gradient.cwiseAbs().maxCoeff(), 1e-3) << at.gradient.transpose();
  EXPECT_LT(a.gradient_evaluations, b.gradient_evaluations);
}

// A warm start with the previous result's curvature: quasi-Newton steps on
// all the points straight away (no restarts on subsets). From the optimum
// itself one gradient shows there is nothing to gain; after more touches the
// climb ends where a cold search ends.
TEST(GpHyperparameterSearch, WarmStartWithCurvatureClimbsOnAllPoints) {
  const Eigen::MatrixX2d xy = random_xy(700, 45);
  const Eigen::VectorXd z = heights(xy, 0.05);
  SearchOptions cold;
  cold.screening_points = 200;
  const SearchResult first = select_hyperparameters(xy.topRows(600), z.head(600), cold);
  ASSERT_TRUE(first.hessian_per_point.allFinite());
  ASSERT_GT(first.hessian_per_point.determinant(), 0.0);

  SearchOptions warm = cold;
  warm.start_hyperparameters = {first.hyperparameters};
  warm.start_hessian_per_point = first.hessian_per_point;
  const SearchResult again = select_hyperparameters(xy.topRows(600), z.head(600), warm);
  EXPECT_TRUE(again.screening.empty());
  EXPECT_EQ(again.gradient_evaluations, 1);
  EXPECT_GE(again.lml, first.lml - 1e-9 * std::abs(first.lml));

  const SearchResult grown = select_hyperparameters(xy, z, warm);
  const SearchResult reference = select_hyperparameters(xy, z, cold);
  EXPECT_TRUE(grown.screening.empty());
  EXPECT_LE(grown.gradient_evaluations, 5);
  EXPECT_GE(grown.lml, reference.lml - 1e-8 * std::abs(reference.lml));
  EXPECT_NEAR(grown.hyperparameters.lengthscale_mm / reference.hyperparameters.lengthscale_mm, 1.0, 1e-4);
  EXPECT_GE(grown.lml, grown.initial_lml);
}

// A warm start (the previous touch's optimum) replaces the default starts.
TEST(GpHyperparameterSearch, WarmStartIsUsedAndClamped) {
  const Eigen::MatrixX2d xy = random_xy(100, 43);
  const Eigen::VectorXd z = heights(xy, 0.1);
  SearchOptions options;
  options.start_hyperparameters = {{2.0, 12.0, 0.01}, {2.0, 1e9, 0.01}};
  const SearchResult r = select_hyperparameters(xy, z, options);
  ASSERT_EQ(r.starts.size(), 2u);
  EXPECT_NEAR(r.starts[0].start.lengthscale_mm, 12.0, 1e-9);
  EXPECT_NEAR(r.starts[1].start.lengthscale_mm / r.bounds.upper.lengthscale_mm, 1.0, 1e-4);
  EXPECT_GE(r.lml, r.initial_lml);
}

// Case 10: restarts, on a likelihood with two separated maxima in log l
// (the lower one near the first start): the best restart wins.
TEST(GpHyperparameterSearch, RestartsKeepTheBestOptimum) {
  const HyperparameterBounds bounds{{1e-2, 1e-2, 1e-4}, {1e2, 1e3, 1.0}};
  // Peaks at log l = 0 (height 1) and log l = 4 (height 3), quadratic elsewhere.
  const LmlFunction f = [](const LogHyperparameters& t, double& value, Eigen::Vector3d* g) {
    const double a = t[1], b = t[1] - 4.0;
    const double pa = std::exp(-a * a), pb = 3.0 * std::exp(-b * b);
    value = pa + pb - 0.5 * (t[0] * t[0] + (t[2] + 3.0) * (t[2] + 3.0));
    if (g) *g << -t[0], -2 * a * pa - 2 * b * pb, -(t[2] + 3.0);
    return true;
  };
  SearchOptions options;
  const std::vector<Hyperparameters> starts = {{1.5, std::exp(0.3), 0.1}, {1.0, std::exp(3.5), 0.1}};
  const SearchResult r = maximise_lml(f, bounds, starts, options);
  ASSERT_EQ(r.starts.size(), 2u);
  EXPECT_NEAR(std::log(r.starts[0].result.lengthscale_mm), 0.0, 1e-3);
  EXPECT_NEAR(r.starts[0].lml, 1.0, 1e-6);
  EXPECT_NEAR(std::log(r.hyperparameters.lengthscale_mm), 4.0, 1e-3);
  EXPECT_NEAR(r.lml, 3.0, 1e-6);
  EXPECT_EQ(r.best_start, 1u);
  EXPECT_NEAR(r.hyperparameters.signal_variance_mm2, 1.0, 1e-3);
  EXPECT_NEAR(std::log(r.hyperparameters.noise_variance_mm2), -3.0, 1e-3);
}

// Case 10: evaluations that fail (as a Cholesky failure would) make the line
// search back off; the result is a point that could be evaluated, no worse
// than the start.
TEST(GpHyperparameterSearch, FailedEvaluationsBackOff) {
  const Eigen::MatrixX2d xy = random_xy(100, 34);
  const Eigen::VectorXd z = heights(xy, 0.1);
  MarginalLikelihood lml(KernelKind::rbf, xy, z);
  // The data want l ~ 10 mm; refuse anything above 4 mm. The start (2 mm)
  // climbs towards the refused region.
  const double refuse_above = std::log(4.0);
  int refused = 0;
  const LmlFunction f = [&](const LogHyperparameters& t, double& value, Eigen::Vector3d* g) {
    if (t[1] > refuse_above) {
      ++refused;
      return false;
    }
    const LmlEvaluation e = lml.evaluate(from_log(t), g != nullptr);
    value = e.lml;
    if (g) *g = e.gradient;
    return true;
  };
  const HyperparameterBounds bounds{{1e-3, 0.1, 1e-6}, {1e3, 600.0, 10.0}};
  const SearchResult r = maximise_lml(f, bounds, {{1.0, 2.0, 0.01}}, SearchOptions{});
  EXPECT_GT(r.failed_evaluations, 0);
  EXPECT_EQ(r.failed_evaluations, refused);
  EXPECT_LE(std::log(r.hyperparameters.lengthscale_mm), refuse_above);
  EXPECT_GT(r.hyperparameters.lengthscale_mm, 3.0) << "it should still climb towards the boundary";
  EXPECT_GE(r.lml, r.initial_lml);
  EXPECT_TRUE(std::isfinite(r.lml));
}

// Case 10 on the real failure path: exact duplicate (x, y) whose z differ by
// 1e-7 mm ask for a noise variance of ~1e-14 mm^2 against a signal of a few
// mm^2, the edge of what a Cholesky factorises without jitter (pivots of ~2g
// against n eps ~ 1e-14, g = noise / s2). With no jitter allowed and the noise
// bound far below that edge, the search steps onto covariances that cannot be
// factorised; each such step fails and the line search backs off.
TEST(GpHyperparameterSearch, UnfactorisableStepsOnDuplicatesBackOff) {
  Eigen::MatrixX2d xy = grid_xy(6, 6, 0.0, 50.0);
  Eigen::VectorXd z = heights(xy);
  const Eigen::Index n0 = xy.rows();
  xy.conservativeResize(n0 + 4, 2);
  z.conservativeResize(n0 + 4);
  for (Eigen::Index k = 0; k < 4; ++k) {
    xy.row(n0 + k) = xy.row(7 * (k + 1));
    z[n0 + k] = z[7 * (k + 1)] + 1e-7;
  }
  SearchOptions options;
  options.jitter.max_jitter_tries = 0;
  options.bounds.noise_variance_low = 1e-16;  // x var(z): g down to 1e-20
  options.start_hyperparameters = {{4.0, 10.0, 1e-9}};
  const SearchResult r = select_hyperparameters(xy, z, options);
  EXPECT_GT(r.failed_evaluations, 0);
  ASSERT_EQ(r.starts.size(), 1u);
  EXPECT_EQ(r.starts[0].failed_evaluations, r.failed_evaluations);
  EXPECT_GT(r.initial_lml, kNoLml) << "the start itself factorises";
  EXPECT_TRUE(std::isfinite(r.lml));
  EXPECT_GE(r.lml, r.initial_lml);
  EXPECT_TRUE(r.bounds.contains(r.hyperparameters));
  EXPECT_LT(r.hyperparameters.noise_variance_mm2, 1e-12) << "the noise the duplicates ask for";
  // The result is a point that factorised without jitter, at the LML reported.
  MarginalLikelihood lml(KernelKind::rbf, xy, z, options.jitter);
  const Hyperparameters& h = r.hyperparameters;
  EXPECT_NEAR(lml.evaluate_profiled(h.lengthscale_mm, h.noise_variance_mm2 / h.signal_variance_mm2, r.bounds, false).lml,
              r.lml, 1e-9 * std::abs(r.lml));

  // One jitter try rescues every step: the failures were the factorisation's.
  options.jitter.max_jitter_tries = 1;
  EXPECT_EQ(select_hyperparameters(xy, z, options).failed_evaluations, 0);
}

TEST(GpHyperparameterSearch, AStartThatCannotBeEvaluatedIsSkipped) {
  const Eigen::MatrixX2d xy = random_xy(60, 35);
  MarginalLikelihood lml(KernelKind::rbf, xy, heights(xy, 0.1));
  const LmlFunction f = [&](const LogHyperparameters& t, double& value, Eigen::Vector3d* g) {
    if (t[1] < std::log(2.0)) return false;
    const LmlEvaluation e = lml.evaluate(from_log(t), g != nullptr);
    value = e.lml;
    if (g) *g = e.gradient;
    return true;
  };
  const HyperparameterBounds bounds{{1e-3, 0.1, 1e-6}, {1e3, 600.0, 10.0}};
  const SearchResult r = maximise_lml(f, bounds, {{1.0, 1.0, 0.01}, {1.0, 20.0, 0.01}}, SearchOptions{});
  EXPECT_EQ(r.starts[0].start_lml, kNoLml);
  EXPECT_EQ(r.initial_lml, kNoLml);
  EXPECT_EQ(r.best_start, 1u);
  EXPECT_TRUE(std::isfinite(r.lml));

  const LmlFunction never = [](const LogHyperparameters&, double&, Eigen::Vector3d*) { return false; };
  EXPECT_THROW(maximise_lml(never, bounds, {{1.0, 1.0, 0.01}}, SearchOptions{}), RunError);
}

// Case 4: bounds follow the units; so does the selected lengthscale, and the
// fitted surfaces agree after conversion.
TEST(GpHyperparameterSearch, UnitsScaleBoundsAndResult) {
  const Eigen::MatrixX2d xy = random_xy(120, 36);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const DataScales mm = data_scales(xy, z);
  const DataScales xy_m = data_scales(xy / 1000.0, z);
  const DataScales z_m = data_scales(xy, z / 1000.0);
  const HyperparameterBounds b_mm = bounds_from_scales(mm), b_xy_m = bounds_from_scales(xy_m),
                             b_z_m = bounds_from_scales(z_m);
  EXPECT_NEAR(b_xy_m.lower.lengthscale_mm * 1000.0, b_mm.lower.lengthscale_mm, 1e-12 * b_mm.lower.lengthscale_mm);
  EXPECT_NEAR(b_xy_m.upper.lengthscale_mm * 1000.0, b_mm.upper.lengthscale_mm, 1e-12 * b_mm.upper.lengthscale_mm);
  EXPECT_NEAR(b_z_m.lower.noise_variance_mm2 * 1e6, b_mm.lower.noise_variance_mm2, 1e-12 * b_mm.lower.noise_variance_mm2);
  EXPECT_NEAR(b_z_m.upper.signal_variance_mm2 * 1e6, b_mm.upper.signal_variance_mm2,
              1e-12 * b_mm.upper.signal_variance_mm2);
  EXPECT_EQ(b_z_m.lower.lengthscale_mm, b_mm.lower.lengthscale_mm);

  const SearchResult r_mm = select_hyperparameters(xy, z);
  const SearchResult r_xy_m = select_hyperparameters(xy / 1000.0, z);
  const SearchResult r_z_m = select_hyperparameters(xy, z / 1000.0);
  EXPECT_NEAR(r_xy_m.hyperparameters.lengthscale_mm * 1000.0 / r_mm.hyperparameters.lengthscale_mm, 1.0, 1e-4);
  EXPECT_NEAR(r_z_m.hyperparameters.lengthscale_mm / r_mm.hyperparameters.lengthscale_mm, 1.0, 1e-4);
  EXPECT_NEAR(r_z_m.hyperparameters.signal_variance_mm2 * 1e6 / r_mm.hyperparameters.signal_variance_mm2, 1.0, 1e-3);

  const Eigen::MatrixX2d q = grid_xy(8, 8, 0.0, 60.0);
  ExactGp gp_mm(KernelKind::rbf, r_mm.hyperparameters), gp_m(KernelKind::rbf, r_xy_m.hyperparameters);
  gp_mm.fit(xy, z);
  gp_m.fit(xy / 1000.0, z);
  EXPECT_LT((gp_m.mean(q / 1000.0) - gp_mm.mean(q)).cwiseAbs().maxCoeff(), 1e-4);
}

// Case 3 for selection: a base-frame offset changes nothing.
TEST(GpHyperparameterSearch, ShiftInvariant) {
  const Eigen::MatrixX2d xy = random_xy(100, 37);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const SearchResult near = select_hyperparameters(xy, z);
  const SearchResult far = select_hyperparameters(xy.rowwise() + Eigen::RowVector2d(1e7, -1e6), z.array() + 1e4);
  // The offset leaves ~1e-9 mm of rounding in the centred inputs; the search
  // stops on the LML, which is flat at the optimum, so the lengthscale is
  // pinned to about the square root of the LML's tolerance, not to the bit.
  EXPECT_NEAR(far.hyperparameters.lengthscale_mm / near.hyperparameters.lengthscale_mm, 1.0, 1e-6);
  EXPECT_NEAR(far.lml, near.lml, 1e-8 * std::abs(near.lml));
}

// Case 5 for selection: a flat plate selects finite hyperparameters and its
// surface is the plate.
TEST(GpHyperparameterSearch, ConstantTarget) {
  const Eigen::MatrixX2d xy = random_xy(80, 38);
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(80, -2.5);
  const SearchResult r = select_hyperparameters(xy, z);
  EXPECT_TRUE(std::isfinite(r.lml));
  EXPECT_TRUE(r.bounds.contains(r.hyperparameters));
  ExactGp gp(KernelKind::rbf, r.hyperparameters);
  gp.fit(xy, z);
  const Eigen::MatrixX2d q = grid_xy(6, 6, 0.0, 60.0);
  EXPECT_LT((gp.mean(q).array() + 2.5).abs().maxCoeff(), 1e-12);
  EXPECT_TRUE(gp.variance(q).allFinite());
}

TEST(GpHyperparameterSearch, BadDataIsAnInputError) {
  const Eigen::MatrixX2d two = random_xy(2, 39);
  EXPECT_THROW(select_hyperparameters(two, heights(two)), InputError);
  const Eigen::MatrixX2d same = Eigen::MatrixX2d::Constant(10, 2, 5.0);
  try {
    select_hyperparameters(same, Eigen::VectorXd::LinSpaced(10, 0.0, 1.0));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("share"), std::string::npos) << e.what();
  }
  Eigen::MatrixX2d xy = random_xy(10, 40);
  Eigen::VectorXd z = heights(xy);
  z[4] = std::nan("");
  EXPECT_THROW(select_hyperparameters(xy, z), InputError);
  SearchOptions bad;
  bad.start_lengthscales_mm = {-1.0};
  EXPECT_THROW(select_hyperparameters(random_xy(10, 41), heights(random_xy(10, 41)), bad), InputError);
}

}  // namespace
}  // namespace touchcloud::gp
