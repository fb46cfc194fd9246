// The zero level set meshed by VTK's flying edges: an analytic sphere's
// vertices lie on it, the mesh is closed (every edge in two triangles) with
// the Euler characteristic of its shape, and the implicit surfaces fitted to
// touches of a sphere and a torus give closed meshes of genus 0 and 1 near
// the true surfaces. Bad grids and values are refused.
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
  const gp::SampleGrid grid = gp::grid_around(p, 1.0, 4);
  EXPECT_THROW(gp::zero_level_set(grid, Eigen::VectorXd::Zero(3)), InputError);
  Eigen::VectorXd f = Eigen::VectorXd::Ones(grid.size());
  EXPECT_TRUE(gp::zero_level_set(grid, f).triangles.empty());
  f[5] = std::nan("");
  EXPECT_THROW(gp::zero_level_set(grid, f), InputError);
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
