// Log marginal likelihood and its analytic gradient: hard cases 2 and 11.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "touchcloud/gp/kernel.hpp"
#include "touchcloud/gp/marginal_likelihood.hpp"
#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {
namespace {

using test::heights;
using test::random_xy;

double dense_lml(KernelKind kind, const Hyperparameters& h, const Eigen::MatrixX2d& xy, const Eigen::VectorXd& z) {
  const Kernel k(kind, h);
  const Eigen::Index n = xy.rows();
  Eigen::MatrixXd a(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) a(i, j) = k.covariance((xy.row(i) - xy.row(j)).squaredNorm());
  a.diagonal().array() += h.noise_variance_mm2;
  const Eigen::VectorXd zc = z.array() - z.mean();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
  return -0.5 * zc.dot(ldlt.solve(zc)) - 0.5 * ldlt.vectorD().array().log().sum() -
         0.5 * static_cast<double>(n) * std::log(2.0 * std::numbers::pi);
}

TEST(GpMarginalLikelihood, MatchesDenseFormula) {
  // 300 points: the kernel fill on two threads (touchcloud/gp/triangle_columns.hpp).
  for (int n : {70, 300}) {
  const Eigen::MatrixX2d xy = random_xy(n, 21);
  const Eigen::VectorXd z = heights(xy, 0.1);
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    MarginalLikelihood lml(kind, xy, z);
    for (const Hyperparameters& h : {Hyperparameters{4.0, 9.0, 0.01}, Hyperparameters{0.5, 3.0, 0.2}}) {
      const double expected = dense_lml(kind, h, xy, z);
      EXPECT_NEAR(lml.evaluate(h, false).lml, expected, 1e-9 * std::abs(expected)) << to_string(kind);
      EXPECT_NEAR(lml.evaluate(h, true).lml, expected, 1e-9 * std::abs(expected)) << to_string(kind);
    }
  }
  }
}

// Case 11: central differences in log space, both kernels, several settings
// (well and poorly determined, noise-dominated and nearly noise-free).
TEST(GpMarginalLikelihood, AnalyticGradientMatchesFiniteDifferences) {
  // 120 points: the recursive inverse (> 2 x 64); 400: the BLAS inverse and
  // the column sums on two threads (touchcloud/gp/triangle_columns.hpp).
  for (int n : {120, 400}) {
  const Eigen::MatrixX2d xy = random_xy(n, 22);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const std::vector<Hyperparameters> settings = {
      {4.0, 9.0, 0.01}, {0.3, 2.0, 0.5}, {10.0, 40.0, 1e-3}, {1.0, 6.0, 1e-5}};
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    MarginalLikelihood lml(kind, xy, z);
    for (const Hyperparameters& h : settings) {
      const LmlEvaluation at = lml.evaluate(h, true);
      ASSERT_EQ(at.factorisation.attempts, 1) << "a jitter change would make the difference quotient meaningless";
      // Truncation error ~1e-8 relative; smaller steps drown in rounding when
      // A is ill-conditioned (the l = 6 mm, noise 1e-5 settings).
      const double step = 1e-4;
      for (int i = 0; i < 3; ++i) {
        LogHyperparameters up = to_log(h), down = to_log(h);
        up[i] += step;
        down[i] -= step;
        const double fd = (lml.evaluate(from_log(up), false).lml - lml.evaluate(from_log(down), false).lml) / (2 * step);
        EXPECT_NEAR(at.gradient[i], fd, 1e-6 * std::max(1.0, std::abs(fd)))
            << to_string(kind) << " parameter " << i << " at l = " << h.lengthscale_mm << ", n = " << n;
      }
    }
  }
  }
}

// Case 2: near-duplicates with noise near zero (exact duplicates included, so
// the Matern derivative is evaluated at r = 0): finite LML and gradient.
TEST(GpMarginalLikelihood, NearDuplicatesGiveFiniteValues) {
  const Eigen::MatrixX2d base = random_xy(40, 23);
  for (double gap : {0.0, 1e-12, 1e-9, 1e-6, 1e-4}) {
    Eigen::MatrixX2d xy(80, 2);
    xy << base, base.col(0).array() + gap, base.col(1);
    const Eigen::VectorXd z = heights(xy, 0.05);
    for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
      MarginalLikelihood lml(kind, xy, z);
      for (double noise : {0.0, 1e-14}) {
        const LmlEvaluation e = lml.evaluate({2.0, 8.0, noise}, true);
        EXPECT_TRUE(std::isfinite(e.lml)) << to_string(kind) << " gap " << gap;
        EXPECT_TRUE(e.gradient.allFinite()) << to_string(kind) << " gap " << gap;
        if (gap <= 1e-9) {
          EXPECT_GT(e.factorisation.jitter_mm2, 0.0) << to_string(kind) << " gap " << gap;
        }
      }
    }
  }
}

// The noise derivative must count the noise only, not the jitter: with the
// jitter fixed, d/dlog(noise) of the LML is noise/2 (|alpha|^2 - tr A^-1).
TEST(GpMarginalLikelihood, ZeroNoiseHasZeroNoiseGradient) {
  const Eigen::MatrixX2d xy = random_xy(30, 24);
  MarginalLikelihood lml(KernelKind::rbf, xy, heights(xy));
  EXPECT_EQ(lml.evaluate({1.0, 5.0, 0.0}, true).gradient[2], 0.0);
}

// The profile over s2: its value is the LML at the s2 it reports, and no
// other s2 (at the same noise ratio) does better.
TEST(GpMarginalLikelihood, ProfileIsTheBestSignalVariance) {
  const Eigen::MatrixX2d xy = random_xy(90, 26);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const HyperparameterBounds wide{{1e-6, 0.1, 1e-9}, {1e6, 1e4, 1e3}};
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    MarginalLikelihood lml(kind, xy, z);
    for (const auto& [l, g] : {std::pair{9.0, 1e-3}, std::pair{3.0, 0.1}}) {
      const ProfiledEvaluation p = lml.evaluate_profiled(l, g, wide, false);
      const Hyperparameters& h = p.hyperparameters;
      EXPECT_EQ(h.lengthscale_mm, l);
      EXPECT_NEAR(h.noise_variance_mm2 / h.signal_variance_mm2, g, 1e-14 * g);
      EXPECT_NEAR(lml.evaluate(h, false).lml, p.lml, 1e-10 * std::abs(p.lml)) << to_string(kind);
      for (double f : {0.97, 1.03}) {
        const Hyperparameters other{f * h.signal_variance_mm2, l, f * h.noise_variance_mm2};
        EXPECT_LT(lml.evaluate(other, false).lml, p.lml) << to_string(kind) << " s2 x " << f;
      }
    }
  }
}

// Case 11 for the profile: d/dlog(l, g) against central differences, with s2
// free, held at its upper bound, and s2 set by the upper noise bound.
TEST(GpMarginalLikelihood, ProfiledGradientMatchesFiniteDifferences) {
  const Eigen::MatrixX2d xy = random_xy(120, 27);
  const Eigen::VectorXd z = heights(xy, 0.1);
  const HyperparameterBounds wide{{1e-6, 0.1, 1e-9}, {1e6, 1e4, 1e3}};
  const HyperparameterBounds low_s2{{1e-6, 0.1, 1e-9}, {0.5, 1e4, 1e3}};  // the free s2 is ~4-10 mm^2
  const HyperparameterBounds low_noise{{1e-6, 0.1, 1e-9}, {1e6, 1e4, 1e-3}};
  for (KernelKind kind : {KernelKind::rbf, KernelKind::matern52}) {
    MarginalLikelihood lml(kind, xy, z);
    for (const HyperparameterBounds* b : {&wide, &low_s2, &low_noise}) {
      const double l = 8.0, g = 2e-3;
      const ProfiledEvaluation at = lml.evaluate_profiled(l, g, *b, true);
      ASSERT_EQ(at.factorisation.attempts, 1);
      if (b == &low_s2) {
        EXPECT_EQ(at.hyperparameters.signal_variance_mm2, 0.5);
      }
      if (b == &low_noise) {
        EXPECT_NEAR(at.hyperparameters.noise_variance_mm2, 1e-3, 1e-15);
      }
      const double step = 1e-4;
      for (int i = 0; i < 2; ++i) {
        const double up = std::exp(step * (i == 0)), down = std::exp(-step * (i == 0));
        const double gu = std::exp(step * (i == 1)), gd = std::exp(-step * (i == 1));
        const double fd = (lml.evaluate_profiled(l * up, g * gu, *b, false).lml -
                           lml.evaluate_profiled(l * down, g * gd, *b, false).lml) /
                          (2 * step);
        EXPECT_NEAR(at.gradient[i], fd, 1e-6 * std::max(1.0, std::abs(fd)))
            << to_string(kind) << " parameter " << i
            << (b == &wide ? " free" : b == &low_s2 ? " s2 bound" : " noise bound");
      }
    }
  }
}

TEST(GpMarginalLikelihood, BadInputIsAnInputError) {
  Eigen::MatrixX2d xy = random_xy(5, 25);
  Eigen::VectorXd z = heights(xy);
  xy(0, 0) = std::nan("");
  EXPECT_THROW(MarginalLikelihood(KernelKind::rbf, xy, z), InputError);
  EXPECT_THROW(MarginalLikelihood(KernelKind::rbf, random_xy(5, 25), Eigen::VectorXd::Zero(3)), InputError);
}

}  // namespace
}  // namespace touchcloud::gp
