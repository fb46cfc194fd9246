// SurfaceFit touch by touch, and its summary of what it used: the path each
// touch took (selection on the growth schedule, bordered updates between),
// the selections run and on how many points, the hyperparameters and jitter
// of each surface returned, the inducing points of a sparse fit, and the
// dense algebra and exponential that ran.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/gp/surface_fit.hpp"
#include "touchcloud/gp/vector_exp.hpp"

namespace touchcloud::gp {
namespace {

struct Touch {
  Eigen::MatrixX2d xy;
  Eigen::VectorXd z;
};

// Touch t: a 4 x 3 patch of points 1 mm apart on the fixtures' smooth
// surface, the patches 12 mm apart on a row of three.
Touch patch(int t) {
  Touch touch{test::grid_xy(4, 3, 0.0, 3.0), {}};
  touch.xy.col(0).array() += 8.0 + 12.0 * (t % 3);
  touch.xy.col(1).array() += 8.0 + 12.0 * (t / 3);
  touch.z = test::heights(touch.xy);
  return touch;
}

std::vector<SurfaceModelPtr> add_touches(SurfaceFit& fit, int touches, std::mt19937_64& rng) {
  std::vector<SurfaceModelPtr> surfaces;
  for (int t = 0; t < touches; ++t) {
    const Touch touch = patch(t);
    surfaces.push_back(fit.add(touch.xy, touch.z, rng));
  }
  return surfaces;
}

// Growth 0.5 on touches of 12 points: selections at 12, 24 (>= 18), 36
// (>= 36) and 60 (>= 54) points; 48 (< 54) extends the factor.
TEST(GpSurfaceFit, SummaryRecordsEachTouchsPathAndSelection) {
  SurfaceFitOptions options;
  SurfaceFit fit(options);
  std::mt19937_64 rng(1);
  const std::vector<SurfaceModelPtr> surfaces = add_touches(fit, 5, rng);
  const SurfaceFitSummary& s = fit.summary();
  EXPECT_EQ(s.given.reselect_growth, 0.5);
  EXPECT_EQ(s.selections, 4);
  ASSERT_EQ(s.touches.size(), 5u);
  const std::vector<TouchPath> paths = {TouchPath::selected, TouchPath::selected, TouchPath::selected,
                                        TouchPath::bordered, TouchPath::selected};
  for (std::size_t t = 0; t < s.touches.size(); ++t) {
    SCOPED_TRACE(t);
    const TouchSummary& touch = s.touches[t];
    EXPECT_EQ(touch.path, paths[t]) << to_string(touch.path);
    EXPECT_EQ(touch.points_added, 12);
    EXPECT_EQ(touch.training_points, 12 * static_cast<Eigen::Index>(t + 1));
    EXPECT_EQ(surfaces[t]->training_size(), static_cast<std::size_t>(touch.training_points));
    ASSERT_EQ(touch.selection.has_value(), touch.path == TouchPath::selected);
    if (touch.selection) {
      EXPECT_EQ(touch.selection->points, touch.training_points);  // selection_points 0: all
      EXPECT_GT(touch.selection->evaluations, 0);
      EXPECT_TRUE(std::isfinite(touch.selection->lml));
      EXPECT_EQ(touch.selection->hyperparameters, touch.hyperparameters);
    }
    // What the summary says is what the surface returned holds.
    const auto named = surfaces[t]->hyperparameters();
    EXPECT_EQ(named.at("lengthscale_mm"), touch.hyperparameters.lengthscale_mm);
    EXPECT_EQ(named.at("noise_variance_mm2"), touch.hyperparameters.noise_variance_mm2);
    ASSERT_TRUE(touch.jitter_mm2);
    EXPECT_EQ(named.at("jitter_mm2"), *touch.jitter_mm2);
    EXPECT_FALSE(touch.inducing_points);
    EXPECT_TRUE(touch.refactorised_because.empty()) << touch.refactorised_because;
  }
  // The bordered update keeps the last selection's hyperparameters.
  EXPECT_EQ(s.touches[3].hyperparameters, s.touches[2].hyperparameters);
  // What ran: the dense algebra, its threads and the kernel's exponential.
  EXPECT_EQ(s.dense_algebra, factor_algebra_backend());
  EXPECT_EQ(s.blas_threads, factor_algebra_threads());
  EXPECT_EQ(s.kernel_exp, vector_exp_path());
  EXPECT_FALSE(s.matern_mean_sums);  // rbf
}

TEST(GpSurfaceFit, FewPointsTakeTheInitialLengthscaleAndNothingNewGivesTheSameSurface) {
  SurfaceFitOptions options;
  options.kernel = KernelKind::matern52;
  options.initial_lengthscale_mm = 4.0;
  SurfaceFit fit(options);
  EXPECT_TRUE(fit.summary().matern_mean_sums);
  std::mt19937_64 rng(1);
  const Touch two{test::grid_xy(2, 1, 0.0, 1.0), Eigen::VectorXd::Constant(2, 5.0)};
  fit.add(two.xy, two.z, rng);
  const Touch touch = patch(0);
  const SurfaceModelPtr fitted = fit.add(touch.xy, touch.z, rng);
  const SurfaceModelPtr again = fit.add(Eigen::MatrixX2d(0, 2), Eigen::VectorXd(0), rng);
  EXPECT_EQ(again, fitted);
  const SurfaceFitSummary& s = fit.summary();
  EXPECT_EQ(s.selections, 1);
  ASSERT_EQ(s.touches.size(), 3u);
  EXPECT_EQ(s.touches[0].path, TouchPath::unchanged);
  EXPECT_FALSE(s.touches[0].selection);
  EXPECT_EQ(s.touches[0].hyperparameters.lengthscale_mm, 4.0);
  EXPECT_EQ(s.touches[1].path, TouchPath::selected);
  EXPECT_EQ(s.touches[2].path, TouchPath::unchanged);
  EXPECT_EQ(s.touches[2].points_added, 0);
  EXPECT_EQ(s.touches[2].training_points, 14);
  EXPECT_EQ(s.touches[2].hyperparameters, s.touches[1].hyperparameters);
}

TEST(GpSurfaceFit, ATouchWithABadPointIsRefusedWhole) {
  SurfaceFit fit(SurfaceFitOptions{});
  std::mt19937_64 rng(1);
  add_touches(fit, 2, rng);
  Touch bad = patch(2);
  bad.z[5] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(fit.add(bad.xy, bad.z, rng), InputError);
  EXPECT_EQ(fit.summary().touches.size(), 2u);
  const Touch good = patch(2);
  fit.add(good.xy, good.z, rng);
  EXPECT_EQ(fit.summary().touches.back().training_points, 36);
}

// Method sparse: every touch refits on inducing points (a farthest-point
// subset of at most inducing_points), and the selection runs on at most as
// many points.
TEST(GpSurfaceFit, SparseRecordsInducingPointsAndTheSelectionSubset) {
  SurfaceFitOptions options;
  options.method = FitMethod::sparse;
  options.inducing_points = 20;
  options.reselect_growth = 100.0;
  SurfaceFit fit(options);
  std::mt19937_64 rng(1);
  add_touches(fit, 3, rng);
  const SurfaceFitSummary& s = fit.summary();
  EXPECT_EQ(s.selections, 1);
  ASSERT_EQ(s.touches.size(), 3u);
  ASSERT_TRUE(s.touches[0].selection);
  EXPECT_EQ(s.touches[0].selection->points, 12);
  for (std::size_t t = 0; t < s.touches.size(); ++t) {
    SCOPED_TRACE(t);
    const TouchSummary& touch = s.touches[t];
    EXPECT_EQ(touch.path, t == 0 ? TouchPath::selected : TouchPath::unchanged);
    ASSERT_TRUE(touch.inducing_points);
    EXPECT_EQ(*touch.inducing_points, std::min<Eigen::Index>(20, touch.training_points));
    ASSERT_TRUE(touch.vfe_bound);
    EXPECT_TRUE(std::isfinite(*touch.vfe_bound));
    EXPECT_FALSE(touch.jitter_mm2);
  }

  options.reselect_growth = 0.0;
  SurfaceFit every(options);
  add_touches(every, 3, rng);
  EXPECT_EQ(every.summary().selections, 3);
  EXPECT_EQ(every.summary().touches.back().selection->points, 20);  // of 36: inducing_points
}

}  // namespace
}  // namespace touchcloud::gp
