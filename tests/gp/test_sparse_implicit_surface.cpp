// The sparse (inducing-point) implicit surface against the exact one on the
// same touches: its mean on the exact zero level set and on a grid band
// around it, its variance there, the sphere's radius it recovers, the
// torus's sign inside and outside, and the exact form's refusal beyond its
// point count.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "implicit_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/gp/implicit_surface.hpp"
#include "touchcloud/gp/level_set_mesh.hpp"
#include "touchcloud/gp/sparse_implicit_surface.hpp"

using namespace touchcloud;
using touchcloud::test::SphereObject;
using touchcloud::test::TorusObject;
using touchcloud::test::one_row;

namespace {

gp::ImplicitSurfaceOptions matern_options() {
  gp::ImplicitSurfaceOptions o;
  o.kernel = gp::ImplicitKernelKind::matern52;
  return o;
}

Eigen::MatrixX3d vertices_of(const scoring::TriangleMesh& mesh) {
  Eigen::MatrixX3d v(static_cast<Eigen::Index>(mesh.vertices.size()), 3);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) v.row(static_cast<Eigen::Index>(i)) = mesh.vertices[i];
  return v;
}

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / static_cast<double>(v.size())); }

}  // namespace

// 100 touches over a sphere of 20 mm (2,100 training points, where the exact
// form is still quick), inducing sites 5 mm apart (204 inducing points).
// Measured: on the exact zero level set the sparse mean is within 0.021 mm
// of 0 (rms 0.009), its variance there within 0.0007 mm^2 of the exact one
// (the sparse variance is the larger, as VFE's is), and on the grid samples
// within two offsets of that surface the two means differ by at most 0.065 mm
// (rms 0.015); tolerances about twice that.
TEST(SparseImplicitSurface, MatchesExactOnSphere) {
  const auto touches = SphereObject().touches(100);
  gp::ImplicitSurface exact(matern_options());
  gp::SparseImplicitSurface sparse(matern_options(), {5.0});
  int bordered = 0;
  for (const auto& t : touches) {
    exact.add(t);
    bordered += sparse.add(t).path == gp::ImplicitUpdatePath::bordered;
  }
  EXPECT_GT(bordered, 80) << "most touches extend the sparse form";
  EXPECT_LT(sparse.inducing_size(), exact.training_size() / 5);
  EXPECT_EQ(sparse.hyperparameters().lengthscale_mm, exact.hyperparameters().lengthscale_mm);

  const gp::SampleGrid grid = gp::grid_around(exact.contact_points(), 5.0, 32);
  const Eigen::MatrixX3d q = grid.sample_points();
  const Eigen::VectorXd exact_mean = exact.mean(q);
  const Eigen::MatrixX3d on_surface = vertices_of(gp::zero_level_set(grid, exact_mean));
  ASSERT_GT(on_surface.rows(), 1000);
  const Eigen::VectorXd there = sparse.mean(on_surface);
  EXPECT_LT(there.cwiseAbs().maxCoeff(), 0.05);
  EXPECT_LT(rms(there), 0.02);
  const Eigen::VectorXd dv = sparse.variance(on_surface) - exact.variance(on_surface);
  EXPECT_LT(dv.cwiseAbs().maxCoeff(), 0.002);

  // The grid band the mesher crosses: samples within two offsets of the exact surface.
  const Eigen::VectorXd sparse_mean = sparse.mean(q);
  std::vector<Eigen::Index> band;
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    if (std::abs(exact_mean[i]) <= 2 * exact.options().offset_mm) band.push_back(i);
  ASSERT_GT(band.size(), 1000u);
  const Eigen::VectorXd dm = sparse_mean(band) - exact_mean(band);
  EXPECT_LT(dm.cwiseAbs().maxCoeff(), 0.15);
  EXPECT_LT(rms(dm), 0.04);
  const Eigen::VectorXd v = sparse.variance(q);
  EXPECT_TRUE(v.allFinite());
  EXPECT_GE(v.minCoeff(), 0.0);
}

// The sparse form alone: the sphere's radius along 26 rays within 0.25 mm
// (the exact form's tolerance), and the torus's sign: its tube inside, its
// hole and beyond outside.
TEST(SparseImplicitSurface, SphereRadiusAndTorusSign) {
  const SphereObject sphere;
  gp::SparseImplicitSurface s(matern_options(), {5.0});
  for (const auto& t : sphere.touches(100)) s.add(t);
  EXPECT_LT(test::worst_radius_error(s, sphere), 0.25);

  const TorusObject torus;
  gp::SparseImplicitSurface ring(matern_options(), {5.0});
  for (const auto& t : torus.touches(12, 6)) ring.add(t);
  EXPECT_GT(ring.mean(one_row(Eigen::Vector3d::Zero()))[0], 0) << "the hole's centre is outside";
  EXPECT_GT(ring.mean(one_row({0, 0, 30}))[0], 0);
  EXPECT_GT(ring.mean(one_row({60, 0, 0}))[0], 0);
  for (int i = 0; i < 8; ++i) {
    const double u = 2 * std::numbers::pi * (i + 0.25) / 8;
    EXPECT_LT(ring.mean(one_row(torus.major_mm * Eigen::Vector3d(std::cos(u), std::sin(u), 0)))[0], 0) << u;
  }
  const Eigen::VectorXd v = ring.variance(gp::grid_around(ring.contact_points(), 5.0, 16).sample_points());
  EXPECT_TRUE(v.allFinite());
  EXPECT_GE(v.minCoeff(), 0.0);
}

// The exact form refuses, unchanged, a touch that would take it beyond
// max_training_points, naming the sparse form; the touch before fits.
TEST(SparseImplicitSurface, ExactRefusesBeyondItsPointCount) {
  const auto touches = SphereObject().touches(3);  // 21 training points each
  gp::ImplicitSurfaceOptions o = matern_options();
  o.max_training_points = 50;
  gp::ImplicitSurface exact(o);
  exact.add(touches[0]);
  exact.add(touches[1]);
  try {
    exact.add(touches[2]);
    FAIL() << "63 training points accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sparse"), std::string::npos) << e.what();
  }
  EXPECT_EQ(exact.training_size(), 42);
  EXPECT_EQ(exact.touches(), 2u);
}

TEST(SparseImplicitSurface, RefusesBadSpacing) {
  EXPECT_THROW(gp::SparseImplicitSurface(matern_options(), {0.0}), InputError);
  EXPECT_THROW(gp::SparseImplicitSurface(matern_options(), {std::nan("")}), InputError);
  EXPECT_THROW(gp::SparseImplicitSurface(matern_options(), {5.0}).mean(one_row(Eigen::Vector3d::Zero())), InputError);
}

// As ImplicitSurface.ASweptApproachOpensTheSpaceAPressWentThrough, in the
// sparse form: the mouth, far from every contact, holds no inducing site of
// a signed pair, so the swept points become sites of their own, and open it.
// Sites 8 mm apart take every other swept point: between them the mean
// swings about the distance from the floor: by 1.5 mm next to it, 3.4 mm at 44 mm.
TEST(SparseImplicitSurface, ASweptApproachOpensTheSpaceAPressWentThrough) {
  std::vector<gp::ImplicitTouch> touches = test::cup_and_floor_press(2.5);
  const auto fitted = [&]() {
    gp::SparseImplicitSurface s(matern_options(), {8.0});
    for (const auto& t : touches) s.add(t);
    return s;
  };
  const gp::SparseImplicitSurface closed = fitted();
  gp::add_swept_approach(touches.back(), {0, 0, 10}, Eigen::Vector3d::UnitZ(), 80, 4);
  const gp::SparseImplicitSurface open = fitted();
  EXPECT_LT(closed.mean(one_row({0, 0, 75}))[0], -5) << "the mouth is closed without the approach";
  EXPECT_GT(open.inducing_size(), closed.inducing_size());
  for (double z = 14; z <= 86; z += 4)  // the last swept point, at 90, falls within 8 mm of the site at 86
    EXPECT_NEAR(open.mean(one_row({0, 0, z}))[0], z - 10, 2.0 + 0.05 * (z - 10)) << "on the axis at z = " << z;
}
