// Uniform area sampling of meshes: points on the surface, triangles hit in
// proportion to their area, seeded reproducibility independent of threads,
// a mesh's samples scoring ~0 against themselves, and the sampling bias that
// docs/scoring.md derives for the default density.
#include <gtest/gtest.h>

#include <cmath>

#include "touchcloud/error.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

using namespace touchcloud;
using scoring::NearestPointIndex;
using scoring::Points;
using scoring::TriangleMesh;

namespace {

// An axis-aligned cube of side `side` centred on the origin: 12 triangles.
TriangleMesh cube(double side) {
  TriangleMesh m;
  const double h = side / 2;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  const std::uint32_t quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

// A square of side `side` in the z = 0 plane, from the origin: 2 triangles.
TriangleMesh square(double side) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {side, 0, 0}, {side, side, 0}, {0, side, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

}  // namespace

TEST(SurfaceSampling, AreaOfACubeAndASquare) {
  EXPECT_DOUBLE_EQ(scoring::surface_area_mm2(cube(10)), 600.0);
  EXPECT_DOUBLE_EQ(scoring::surface_area_mm2(square(100)), 10000.0);
}

TEST(SurfaceSampling, PointsLieOnTheSurface) {
  for (const auto& p : scoring::sample_surface(cube(10), 20000, 1)) {
    EXPECT_NEAR(p.cwiseAbs().maxCoeff(), 5.0, 1e-12);  // on a face of the cube
    EXPECT_LE(p.cwiseAbs().maxCoeff(), 5.0 + 1e-12);
  }
}

TEST(SurfaceSampling, TrianglesAreHitInProportionToTheirArea) {
  // Two triangles sharing an edge, of areas 1/2 and 3/2 (1:3), plus a
  // degenerate one that must never be hit.
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -3, 0}, {2, 0, 0}};
  m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 1, 4}};
  const std::size_t n = 100000;
  std::size_t upper = 0;
  Eigen::Vector3d sum_upper = Eigen::Vector3d::Zero();
  for (const auto& p : scoring::sample_surface(m, n, 7)) {
    EXPECT_EQ(p.z(), 0.0);
    if (p.y() > 0) ++upper, sum_upper += p;
    else EXPECT_LE(p.x() - p.y() / 3, 1.0 + 1e-12);  // inside the lower triangle
  }
  // Binomial(n, 1/4): sd = sqrt(n * 3/16) ~ 137 points; allow 5 sd.
  EXPECT_NEAR(static_cast<double>(upper), n / 4.0, 5 * std::sqrt(n * 3.0 / 16));
  // Uniform inside: the mean of a triangle's points is its centroid (1/3, 1/3);
  // sd of a coordinate is sqrt(1/18) / sqrt(25000) ~ 0.0015.
  const Eigen::Vector3d centroid = sum_upper / static_cast<double>(upper);
  EXPECT_NEAR(centroid.x(), 1.0 / 3, 0.008);
  EXPECT_NEAR(centroid.y(), 1.0 / 3, 0.008);
}

TEST(SurfaceSampling, SeededAndIndependentOfThreads) {
  const TriangleMesh m = cube(10);
  const Points a = scoring::sample_surface(m, 200000, 42, 1);
  const Points b = scoring::sample_surface(m, 200000, 42, 3);
  const Points c = scoring::sample_surface(m, 200000, 43, 1);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(SurfaceSampling, RefusesAMeshWithoutArea) {
  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};  // collinear
  flat.triangles = {{0, 1, 2}};
  EXPECT_THROW(scoring::sample_surface(flat, 10, 0), InputError);
  TriangleMesh broken = square(1);
  broken.triangles.push_back({0, 1, 9});
  EXPECT_THROW(scoring::sample_surface(broken, 10, 0), InputError);
}

TEST(SurfaceSampling, AMeshScoresAboutZeroAgainstItself) {
  // Two independent samplings of one cube: the chamfer between them is only
  // the sampling gap, 1 / (2 sqrt(rho)) on average for a point on a surface
  // sampled rho points per mm^2: 300k points on 600 mm^2 (500 per mm^2) give
  // 0.022 mm est -> gt; the 5000 estimated points (8.3 per mm^2) leave
  // 0.173 mm the other way.
  const TriangleMesh m = cube(10);
  const NearestPointIndex gt(scoring::sample_surface(m, 300000, 1));
  const Points est = scoring::sample_surface(m, 5000, 2);
  const auto s = scoring::score_estimate(est, gt);
  EXPECT_GT(s.chamfer_est_to_gt_mm, 0.0);
  EXPECT_NEAR(s.chamfer_est_to_gt_mm, 1 / (2 * std::sqrt(500.0)), 0.003);
  EXPECT_NEAR(s.chamfer_gt_to_est_mm, 1 / (2 * std::sqrt(5000 / 600.0)), 0.025);
}

TEST(SurfaceSampling, DefaultDensityBiasMatchesTheDocs) {
  // docs/scoring.md: with the default 100 samples per mm^2, a point h above
  // the surface is scored sqrt(h^2 + r^2) instead of h, r the distance to the
  // nearest sample; on average about 1 / (2 pi rho h) = 0.0016 mm at h = 1 mm.
  const TriangleMesh m = square(100);
  const std::size_t n = scoring::default_mesh_samples(scoring::surface_area_mm2(m));
  EXPECT_EQ(n, 1000000u);
  const NearestPointIndex gt(scoring::sample_surface(m, n, 3));
  Points est;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) est.emplace_back(5 + 0.9 * i, 5 + 0.9 * j, 1.0);
  scoring::ScoreOptions o;
  o.metrics = scoring::MetricSelection::parse({"chamfer_est_to_gt"});
  const double bias = scoring::score_estimate(est, gt, o).chamfer_est_to_gt_mm - 1.0;
  EXPECT_GT(bias, 0.0);
  EXPECT_NEAR(bias, 1 / (2 * M_PI * 100 * 1.0), 0.0004);
}

TEST(SurfaceSampling, DefaultCountFollowsTheArea) {
  EXPECT_EQ(scoring::default_mesh_samples(10000.0), 1000000u);
  EXPECT_EQ(scoring::default_mesh_samples(12.0), scoring::kMinMeshSamples);
  EXPECT_EQ(scoring::default_mesh_samples(1e9), scoring::kMaxMeshSamples);
}
