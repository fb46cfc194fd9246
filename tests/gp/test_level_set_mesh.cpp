// The zero level set meshed by VTK's flying edges: an analytic sphere's
// vertices lie on it, the mesh is closed (every edge in two triangles) with
// the Euler characteristic of its shape, and the implicit surfaces fitted to
// touches of a sphere and a torus give closed meshes of genus 0 and 1 near
// the true surfaces. Bad grids and values are refused. A piece of the mesh
// far from every touched point is dropped, and nothing else.
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <gtest/gtest.h>

#include "implicit_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/gp/implicit_surface.hpp"
#include "touchcloud/gp/level_set_mesh.hpp"

using namespace touchcloud;

namespace {

// Edges in other than two triangles, and V - E + F.
struct Topology {
  std::size_t open_edges = 0;
  long euler = 0;
};
Topology topology(const scoring::TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) ++edges[std::minmax(t[i], t[(i + 1) % 3])];
  Topology out;
  for (const auto& [edge, count] : edges) out.open_edges += count != 2;
  out.euler = static_cast<long>(mesh.vertices.size()) - static_cast<long>(edges.size()) +
              static_cast<long>(mesh.triangles.size());
  return out;
}

gp::ImplicitSurface fitted(const std::vector<gp::ImplicitTouch>& touches) {
  gp::ImplicitSurfaceOptions o;
  o.reselect_growth = 1.0;
  o.selection_points = 200;
  gp::ImplicitSurface s(o);
  for (const auto& t : touches) s.add(t);
  return s;
}

scoring::TriangleMesh mesh_of(const gp::ImplicitSurface& s, int cells) {
  const gp::SampleGrid grid = gp::grid_around(s.contact_points(), 5.0, cells);
  return gp::zero_level_set(grid, s.mean(grid.sample_points()));
}

}  // namespace

TEST(LevelSetMesh, AnalyticSphere) {
  Eigen::MatrixX3d corners(2, 3);
  corners << -10, -10, -10, 10, 10, 10;
  const gp::SampleGrid grid = gp::grid_around(corners, 2.0, 48);
  EXPECT_EQ(grid.points, Eigen::Vector3i::Constant(49));
  const Eigen::VectorXd f = grid.sample_points().rowwise().norm().array() - 10.0;
  const scoring::TriangleMesh mesh = gp::zero_level_set(grid, f);
  ASSERT_GT(mesh.triangles.size(), 1000u);
  double worst = 0;
  for (const auto& v : mesh.vertices) worst = std::max(worst, std::abs(v.norm() - 10.0));
  EXPECT_LT(worst, 0.01);  // |p| is linear along grid edges to ~(spacing / r)^2 r
  const Topology t = topology(mesh);
  EXPECT_EQ(t.open_edges, 0u);
  EXPECT_EQ(t.euler, 2);
  // Triangles face the positive side (outwards): the enclosed volume, by
  // the divergence theorem, is positive and that of the sphere.
  double volume = 0;
  for (const auto& tri : mesh.triangles)
    volume += mesh.vertices[tri[0]].dot(mesh.vertices[tri[1]].cross(mesh.vertices[tri[2]])) / 6;
  EXPECT_NEAR(volume, 4.0 / 3.0 * std::numbers::pi * 1000, 10);
}

TEST(LevelSetMesh, RefusesBadInput) {
  Eigen::MatrixX3d p(1, 3);
  p << 0, 0, 0;
  EXPECT_THROW(gp::grid_around(Eigen::MatrixX3d(0, 3), 1.0, 8), InputError);
  EXPECT_THROW(gp::grid_around(p, 0.0, 8), InputError);
  EXPECT_THROW(gp::grid_around(Eigen::MatrixX3d(0, 3), 1.0, 8, 0.0), InputError);
  EXPECT_THROW(gp::grid_around(p, 1.0, 8, std::nan("")), InputError);
  const gp::SampleGrid grid = gp::grid_around(p, 1.0, 4);
  EXPECT_THROW(gp::zero_level_set(grid, Eigen::VectorXd::Zero(3)), InputError);
  Eigen::VectorXd f = Eigen::VectorXd::Ones(grid.size());
  EXPECT_TRUE(gp::zero_level_set(grid, f).triangles.empty());
  f[5] = std::nan("");
  EXPECT_THROW(gp::zero_level_set(grid, f), InputError);
}

// A ball of radius 10 mm whose centre is 5 mm above a table: the clipped
// field's level set is the ball above the table, closed by a flat disc of
// radius sqrt(10^2 - 5^2) on it; unclipped, the whole ball.
TEST(LevelSetMesh, TheTableClosesAnObjectStandingOnIt) {
  Eigen::MatrixX3d corners(2, 3);
  corners << -10, -10, -5, 10, 10, 15;
  const double table_z = 0;
  const gp::SampleGrid grid = gp::grid_around(corners, 2.0, 48, table_z);
  // The table's plane midway between two layers of samples.
  const double layers = (table_z - grid.origin_mm.z()) / grid.spacing_mm;
  EXPECT_NEAR(layers - std::floor(layers), 0.5, 1e-9);
  EXPECT_GE(grid.origin_mm.z() + grid.spacing_mm * (grid.points.z() - 1), 15.0 + 2.0);
  const Eigen::MatrixX3d at = grid.sample_points();
  const Eigen::VectorXd ball = (at.rowwise() - Eigen::RowVector3d(0, 0, 5)).rowwise().norm().array() - 10.0;
  double lowest = 0;
  for (const auto& v : gp::zero_level_set(grid, ball).vertices) lowest = std::min(lowest, v.z());
  EXPECT_LT(lowest, -4.9) << "unclipped: the ball below the table";

  Eigen::VectorXd clipped = ball;
  gp::clip_above_table(grid, table_z, clipped);
  const scoring::TriangleMesh mesh = gp::zero_level_set(grid, clipped);
  const Topology t = topology(mesh);
  EXPECT_EQ(t.open_edges, 0u);
  EXPECT_EQ(t.euler, 2);
  double cap_area = 0, worst_ball = 0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    const double area = (b - a).cross(c - a).norm() / 2;
    if (std::max({std::abs(a.z()), std::abs(b.z()), std::abs(c.z())}) < 1e-9) {
      cap_area += area;
      EXPECT_LT((b - a).cross(c - a).z(), 0.0) << "the cap faces down into the table, outside the object";
    }
  }
  for (const auto& v : mesh.vertices) {
    EXPECT_GE(v.z(), table_z - 1e-9);
    // Above the crease along the rim, where an edge's interpolation mixes the ball and the plane.
    if (v.z() > grid.spacing_mm) worst_ball = std::max(worst_ball, std::abs((v - Eigen::Vector3d(0, 0, 5)).norm() - 10.0));
  }
  EXPECT_LT(worst_ball, 0.01);
  // The disc of radius r = sqrt(75), less at most a cell-wide ring at its
  // rim, where the triangles bend up to the ball.
  const double r = std::sqrt(75.0);
  EXPECT_LE(cap_area, std::numbers::pi * r * r);
  EXPECT_GE(cap_area, std::numbers::pi * (r - grid.spacing_mm) * (r - grid.spacing_mm));
  Eigen::VectorXd too_few = ball.head(3);
  EXPECT_THROW(gp::clip_above_table(grid, table_z, too_few), InputError);
}

// Touches of the sphere (40) and the torus (72): closed meshes of genus 0
// and 1 whose vertices lie within 0.5 mm of the true surfaces (the grid's
// 1.6 mm cells and the GP's error together).
TEST(LevelSetMesh, TouchedSphereAndTorusAreClosed) {
  const test::SphereObject sphere;
  const scoring::TriangleMesh ball = mesh_of(fitted(sphere.touches(40)), 32);
  const Topology tb = topology(ball);
  EXPECT_EQ(tb.open_edges, 0u);
  EXPECT_EQ(tb.euler, 2);
  double worst = 0;
  for (const auto& v : ball.vertices) worst = std::max(worst, std::abs((v - sphere.centre_mm).norm() - sphere.radius_mm));
  EXPECT_LT(worst, 0.5);

  const test::TorusObject torus;
  const scoring::TriangleMesh ring = mesh_of(fitted(torus.touches(12, 6)), 48);
  const Topology tr = topology(ring);
  EXPECT_EQ(tr.open_edges, 0u);
  EXPECT_EQ(tr.euler, 0) << "genus 1";
  worst = 0;
  for (const auto& v : ring.vertices) {
    const double tube = std::hypot(std::hypot(v.x(), v.y()) - torus.major_mm, v.z());
    worst = std::max(worst, std::abs(tube - torus.minor_mm));
  }
  EXPECT_LT(worst, 0.5);
}

// Two spheres' level set, a body of 10 mm touched at six points and a
// bubble of 3 mm touched nowhere, 12 mm from the nearest touched point:
// with a support of 10 mm the bubble goes and the body is kept as it was,
// vertex for vertex; with 15 mm both stay.
TEST(LevelSetMesh, PiecesFarFromEveryTouchAreDropped) {
  Eigen::MatrixX3d corners(2, 3);
  corners << -12, -12, -12, 30, 12, 12;
  const gp::SampleGrid grid = gp::grid_around(corners, 2.0, 64);
  const Eigen::MatrixX3d q = grid.sample_points();
  const Eigen::VectorXd body = q.rowwise().norm().array() - 10.0;
  const Eigen::VectorXd bubble = (q.rowwise() - Eigen::RowVector3d(25, 0, 0)).rowwise().norm().array() - 3.0;
  const scoring::TriangleMesh body_only = gp::zero_level_set(grid, body);
  const scoring::TriangleMesh both = gp::zero_level_set(grid, body.cwiseMin(bubble));
  ASSERT_GT(both.triangles.size(), body_only.triangles.size());
  Eigen::MatrixX3d touched(6, 3);
  touched << 10, 0, 0, -10, 0, 0, 0, 10, 0, 0, -10, 0, 0, 0, 10, 0, 0, -10;

  scoring::TriangleMesh kept = both;
  EXPECT_EQ(gp::drop_unsupported_pieces(kept, touched, 15.0), 0u);
  EXPECT_EQ(kept.triangles.size(), both.triangles.size());

  EXPECT_EQ(gp::drop_unsupported_pieces(kept, touched, 10.0), both.triangles.size() - body_only.triangles.size());
  ASSERT_EQ(kept.vertices.size(), body_only.vertices.size());
  double farthest = 0;
  for (const auto& v : kept.vertices) farthest = std::max(farthest, std::abs(v.norm() - 10.0));
  EXPECT_LT(farthest, 0.01);
  EXPECT_EQ(topology(kept).open_edges, 0u);

  EXPECT_THROW(gp::drop_unsupported_pieces(kept, Eigen::MatrixX3d(0, 3), 5.0), InputError);
  EXPECT_THROW(gp::drop_unsupported_pieces(kept, touched, 0.0), InputError);
  EXPECT_THROW(gp::kept_triangles(kept, std::vector<bool>(3, true)), InputError);
}
