// Objects: the upper surface of a mesh, placed analytic surfaces, and the
// shipped sample objects.
#include <gtest/gtest.h>

#include <random>

#include "touchcloud/simulation/objects/analytic_surfaces.hpp"
#include "touchcloud/simulation/objects/mesh_surface.hpp"
#include "sim_fixture.hpp"
#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

using namespace touchcloud;
using namespace touchcloud::simulation;

namespace {

// The square [0, 10]^2 split in two triangles, on the plane z = 1 + 0.5 x + 0.2 y.
scoring::TriangleMesh tilted_square(double z_offset = 0.0) {
  const auto z = [&](double x, double y) { return 1 + 0.5 * x + 0.2 * y + z_offset; };
  scoring::TriangleMesh m;
  m.vertices = {{0, 0, z(0, 0)}, {10, 0, z(10, 0)}, {10, 10, z(10, 10)}, {0, 10, z(0, 10)}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

}  // namespace

TEST(MeshSurface, IsTheMeshItselfInsideAndTheTableOutside) {
  const MeshSurface surface(tilted_square());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    EXPECT_NEAR(surface.height_mm(p), 1 + 0.5 * p.x() + 0.2 * p.y(), 1e-12);
  }
  EXPECT_NEAR(surface.height_mm({5, 5}), 4.5, 1e-12);  // on the shared diagonal
  EXPECT_EQ(surface.height_mm({-0.5, 5}), 0.0);
  EXPECT_EQ(surface.height_mm({5, 10.5}), 0.0);
  EXPECT_GE(surface.max_height_mm({5, 5}, 20), 1 + 5 + 2);
}

TEST(MeshSurface, TakesTheHighestLayerAndNeverGoesBelowTheTable) {
  scoring::TriangleMesh two = tilted_square();
  const scoring::TriangleMesh top = tilted_square(3.0);
  for (const auto& v : top.vertices) two.vertices.push_back(v);
  for (const auto& t : top.triangles) two.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  EXPECT_NEAR(MeshSurface(two).height_mm({2, 7}), 4 + 1 + 1.4, 1e-12);
  EXPECT_EQ(MeshSurface(tilted_square(-50.0)).height_mm({2, 7}), 0.0);  // sunk below the table
}

TEST(MeshSurface, OverlapIsTheHeightAboveAPointWheneverItIsPositive) {
  // A rough 40 x 40 height field: points around it and just above its cells'
  // highest corners, where the overlap is answered without the height.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  scoring::TriangleMesh m;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) m.vertices.emplace_back(i * 0.7, j * 0.7, 5 + 3 * unit(rng));
  for (int j = 0; j + 1 < 40; ++j)
    for (int i = 0; i + 1 < 40; ++i) {
      const auto a = static_cast<std::uint32_t>(j * 40 + i);
      m.triangles.push_back({a, a + 1, a + 41});
      m.triangles.push_back({a, a + 41, a + 40});
    }
  const MeshSurface surface(m);
  int touching = 0, answered_without_height = 0;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector2d xy(-2 + 31 * unit(rng), -2 + 31 * unit(rng));
    const double height = surface.height_mm(xy);
    const double z = k % 2 ? height + 2 * (unit(rng) - 0.5) : 8.0 + 1e-7 * (unit(rng) - 0.5);
    const double overlap = surface.overlap_mm(xy, z);
    if (height - z > 0) {
      ++touching;
      ASSERT_EQ(overlap, height - z) << k;
    } else {
      ASSERT_LE(overlap, 0.0) << k;
      answered_without_height += overlap != height - z;
    }
  }
  EXPECT_GT(touching, 4000);
  EXPECT_GT(answered_without_height, 2000);
}

TEST(MeshSurface, WallsSeenEdgeOnAreNotSurfaces) {
  scoring::TriangleMesh wall;
  wall.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 0, 5}};
  wall.triangles = {{0, 1, 2}};
  EXPECT_THROW(MeshSurface{wall}, InputError);
}

TEST(AnalyticObject, IsScaledTurnedAndMovedOnTheTable) {
  ObjectSpec spec;
  spec.kind = ObjectKind::FoxMask;
  spec.scale = 2.0;
  spec.base_from_object = Eigen::Translation3d(100, 50, 3) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  const auto surface = make_object_surface(spec);
  // The object point (x, y) lands at (100 - 2y, 50 + 2x), its height doubled and lifted by 3.
  for (const Eigen::Vector2d& local : {Eigen::Vector2d(0, -46), Eigen::Vector2d(-38, 40), Eigen::Vector2d(17, 14)}) {
    const Eigen::Vector2d base(100 - 2 * local.y(), 50 + 2 * local.x());
    EXPECT_NEAR(surface->height_mm(base), 2 * fox_mask().height_mm(local.x(), local.y()) + 3, 1e-9);
  }
  EXPECT_EQ(surface->height_mm({100 + 130, 50}), 0.0);  // beyond the 240 mm footprint: the table
}

TEST(SampleObjects, MeshesMatchTheirAnalyticSurfacesAndGroundTruthLiesOnThem) {
  for (const auto& [name, surface, step] :
       std::vector<std::tuple<std::string, const AnalyticSurface*, double>>{{"fox_mask", &fox_mask(), 2.0},
                                                                            {"wave_surface", &wave_surface(), 1.0}}) {
    const auto folder = touchcloud::test::source_dir() / "sample_clouds" / name;
    const Scene scene = load_scene(folder / "scene.yaml");
    ASSERT_EQ(scene.object.kind, ObjectKind::Mesh) << name;
    const auto mesh = make_object_surface(scene.object);
    // On the vertex lattice the mesh is the analytic surface (float vertices).
    const auto& box = surface->footprint_mm;
    for (double x = box.min().x(); x <= box.max().x(); x += 10 * step)
      for (double y = box.min().y(); y <= box.max().y(); y += 5 * step)
        ASSERT_NEAR(mesh->height_mm({x, y}), surface->height_mm(x, y), 2e-5) << name << " at " << x << ", " << y;
    // The ground truth was sampled from the mesh: every point on it.
    const CloudFile gt = read_cloud_file(folder / "ground_truth.pcd");
    EXPECT_GT(gt.cloud->size(), 20000u) << name;
    for (std::size_t i = 0; i < gt.cloud->size(); i += 97) {
      const auto& p = (*gt.cloud)[i];
      ASSERT_NEAR(mesh->height_mm({p.x, p.y}), p.z, 1e-4) << name << " point " << i;
    }
    EXPECT_EQ(scene.workspace.x_mm, Eigen::Vector2d(box.min().x(), box.max().x())) << name;
  }
  EXPECT_EQ(load_scene(touchcloud::test::source_dir() / "sample_clouds/fox_mask/scene.yaml").workspace.cells(), 14 * 14);
  EXPECT_EQ(load_scene(touchcloud::test::source_dir() / "sample_clouds/wave_surface/scene.yaml").workspace.cells_x, 24);
}
