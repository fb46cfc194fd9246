// The sparse surface (method sparse of SurfaceFit): farthest-point inducing points, and the
// sparse model as a SurfaceModel against the exact one (issue 6).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "gp_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/gp_surface_model.hpp"
#include "touchcloud/gp/inducing_points.hpp"
#include "touchcloud/gp/sparse_surface_model.hpp"
#include "touchcloud/gp/sparse_vfe.hpp"

using namespace touchcloud::gp;

namespace touchcloud::gp {
namespace {

using test::grid_xy;
using test::heights;
using test::random_xy;

Eigen::MatrixX2d rows_of(const Eigen::MatrixX2d& xy, const std::vector<Eigen::Index>& rows) {
  Eigen::MatrixX2d out(static_cast<Eigen::Index>(rows.size()), 2);
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = xy.row(rows[i]);
  return out;
}

// Four corners of a square, its centre and a point next to the centre,
// starting from the centre: after (0, 0) the other corners all lie sqrt(50)
// from the nearest pick, so ties go to the lowest row each time; the point
// next to the centre (1 mm from it) comes last.
TEST(GpInducingPoints, FarthestPointOrderIsDeterministic) {
  Eigen::MatrixX2d xy(6, 2);
  xy << 5, 5,  // centre
      0, 0, 10, 0, 0, 10, 10, 10,  // corners
      6, 5;                        // next to the centre
  EXPECT_EQ(farthest_point_subset(xy, 5, 0), (std::vector<Eigen::Index>{0, 1, 2, 3, 4}));
  EXPECT_EQ(farthest_point_subset(xy, 3, 4), (std::vector<Eigen::Index>{4, 1, 2}))
      << "from (10, 10): (0, 0) at sqrt(200), then (10, 0) and (0, 10) tie at 10";
}

TEST(GpInducingPoints, AllPointsWhenAskedForAsManyAndBadInputRefused) {
  const Eigen::MatrixX2d xy = random_xy(20, 3);
  const std::vector<Eigen::Index> all = farthest_point_subset(xy, 50, 7);
  ASSERT_EQ(all.size(), 20u);
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], static_cast<Eigen::Index>(i));
  EXPECT_THROW(farthest_point_subset(xy, 0, 0), InputError);
  EXPECT_THROW(farthest_point_subset(xy, 5, 20), InputError);
}

// The sparse model with the data as inducing points is the exact GP, through
// the SurfaceModel interface the next-touch stage uses.
TEST(GpSparseSurface, InducingPointsAtTheDataReproduceTheExactModel) {
  const Eigen::MatrixX2d xy = random_xy(300, 71);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Hyperparameters h{4.0, 7.0, 0.0025};
  auto exact = std::make_shared<ExactGp>(KernelKind::rbf, h);
  exact->fit(xy, z);
  auto sparse = std::make_shared<SparseVfeGp>(KernelKind::rbf, h);
  sparse->fit(xy, z, rows_of(xy, farthest_point_subset(xy, 1000, 0)));
  const GpSurfaceModel exact_model(exact, std::nullopt);
  const SparseSurfaceModel sparse_model(sparse, std::nullopt);
  const Eigen::MatrixX2d q = grid_xy(9, 9, 0.0, 60.0);
  EXPECT_EQ(sparse_model.training_size(), 300u);
  // The VFE solves go through K_mm, whose conditioning amplifies the kernel's
  // last-bit rounding (which differs between exp implementations) to ~1e-8.
  EXPECT_LT((sparse_model.mean(q) - exact_model.mean(q)).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((sparse_model.variance(q) - exact_model.variance(q)).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_EQ(sparse_model.hyperparameters().at("inducing_points"), 300.0);
  EXPECT_EQ(sparse_model.hyperparameters().at("lengthscale_mm"), 7.0);
}

// With m < n the sparse mean and variance approach the exact ones as m
// grows (nested farthest-point sets).
TEST(GpSparseSurface, ApproachesTheExactModelAsInducingPointsGrow) {
  const Eigen::MatrixX2d xy = random_xy(600, 72);
  const Eigen::VectorXd z = heights(xy, 0.05);
  const Hyperparameters h{4.0, 8.0, 0.0025};
  ExactGp exact(KernelKind::rbf, h);
  exact.fit(xy, z);
  const Eigen::MatrixX2d q = grid_xy(12, 12, 2.0, 58.0);
  const Eigen::VectorXd mean = exact.mean(q), var = exact.variance(q);
  double previous_mean_error = INFINITY, previous_var_error = INFINITY;
  for (Eigen::Index m : {25, 50, 100, 200, 400}) {
    SparseVfeGp sparse(KernelKind::rbf, h);
    sparse.fit(xy, z, rows_of(xy, farthest_point_subset(xy, m, 0)));
    const double mean_error = (sparse.mean(q) - mean).cwiseAbs().maxCoeff();
    const Eigen::VectorXd sparse_var = sparse.variance(q);
    const double var_error = (sparse_var - var).cwiseAbs().maxCoeff();
    EXPECT_LT(mean_error, previous_mean_error) << m;
    EXPECT_LT(var_error, previous_var_error) << m;
    previous_mean_error = mean_error;
    previous_var_error = var_error;
  }
  // 400 inducing points over the 60 mm square (3 mm apart; lengthscale 8 mm).
  EXPECT_LT(previous_mean_error, 1e-3);
  EXPECT_LT(previous_var_error, 1e-4);
}

}  // namespace
}  // namespace touchcloud::gp
