// make_sample_objects OUT_DIR: writes the sample objects into OUT_DIR
// (sample_clouds/): for the fox mask and the wave surface, a height-field
// mesh of the analytic surface (mesh.ply), ground truth sampled uniformly by
// area from that mesh (ground_truth.pcd) and a scene (scene.yaml). The
// output depends on nothing but this program: rerunning it reproduces the
// files bit for bit.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "touchcloud/simulation/objects/analytic_surfaces.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace fs = std::filesystem;
using touchcloud::simulation::AnalyticSurface;

namespace {

struct SampleObject {
  const AnalyticSurface& surface;
  double mesh_step_mm;      // vertex spacing; puts vertices on the sharp features
  int grid_x, grid_y;       // the paper's sampling grid over the workspace
  const char* description;
};

// Ground truth density: 2 points per mm^2 (mean spacing ~0.7 mm); see README.md.
constexpr double kGroundTruthPointsPerMm2 = 2.0;
constexpr std::uint64_t kGroundTruthSeed = 20240101;

// A grid of vertices over the footprint; each cell split along the diagonal
// whose corners differ less in height, which keeps crests and ridges.
pcl::PolygonMesh height_field_mesh(const SampleObject& object, touchcloud::scoring::TriangleMesh& mesh) {
  const auto& box = object.surface.footprint_mm;
  const int nx = static_cast<int>(std::lround(box.sizes().x() / object.mesh_step_mm)) + 1;
  const int ny = static_cast<int>(std::lround(box.sizes().y() / object.mesh_step_mm)) + 1;
  pcl::PointCloud<pcl::PointXYZ> vertices;
  for (int iy = 0; iy < ny; ++iy)
    for (int ix = 0; ix < nx; ++ix) {
      const double x = box.min().x() + ix * object.mesh_step_mm, y = box.min().y() + iy * object.mesh_step_mm;
      const double z = object.surface.height_mm(x, y);
      vertices.push_back(pcl::PointXYZ(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
      mesh.vertices.emplace_back(x, y, z);
    }
  pcl::PolygonMesh out;
  pcl::toPCLPointCloud2(vertices, out.cloud);
  const auto id = [&](int ix, int iy) { return static_cast<std::uint32_t>(iy * nx + ix); };
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    pcl::Vertices v;
    // Counter-clockwise from above: normals point up.
    v.vertices = {static_cast<pcl::index_t>(a), static_cast<pcl::index_t>(b), static_cast<pcl::index_t>(c)};
    out.polygons.push_back(v);
    mesh.triangles.push_back({a, b, c});
  };
  for (int iy = 0; iy + 1 < ny; ++iy)
    for (int ix = 0; ix + 1 < nx; ++ix) {
      const auto a = id(ix, iy), b = id(ix + 1, iy), c = id(ix + 1, iy + 1), d = id(ix, iy + 1);
      const double ac = std::abs(mesh.vertices[a].z() - mesh.vertices[c].z());
      const double bd = std::abs(mesh.vertices[b].z() - mesh.vertices[d].z());
      if (ac <= bd) {
        add(a, b, c);
        add(a, c, d);
      } else {
        add(a, b, d);
        add(b, c, d);
      }
    }
  return out;
}

std::string scene_yaml(const SampleObject& object) {
  const auto& box = object.surface.footprint_mm;
  std::ostringstream s;
  s << "# " << object.description << "\n"
    << "# Written by make_sample_objects (see ../README.md); the defaults of every\n"
    << "# field are spelled out so that they can be changed here.\n"
    << "name: " << object.surface.name << "\n"
    << "object:\n"
    << "  mesh: mesh.ply            # or 'analytic: " << object.surface.name << "', the surface the mesh samples\n"
    << "  scale: 1.0\n"
    << "  pose: {xyz_mm: [0, 0, 0], rpy_deg: [0, 0, 0]}\n"
    << "workspace:                  # base frame; the paper's sampling grid, positions at cell centres\n"
    << "  x_mm: [" << box.min().x() << ", " << box.max().x() << "]\n"
    << "  y_mm: [" << box.min().y() << ", " << box.max().y() << "]\n"
    << "  grid: [" << object.grid_x << ", " << object.grid_y << "]\n"
    << "sensor:\n"
    << "  gel: {diameter_mm: 65}\n"
    << "  markers: {min_spacing_mm: 1.5, mean_spacing_mm: 1.8, diameter_mm: 0.6, seed: 1}\n"
    << "  plate: {thickness_mm: 5, tilt_deg: [0, 0], mu_air: 1.0, mu_acrylic: 1.49, mu_silicone: 1.41}\n"
    << "  cameras:\n"
    << "    left: {width_px: 1280, height_px: 720, fx_px: 651.5, fy_px: 652.0, cx_px: 598.6, cy_px: 377.1,\n"
    << "           distortion: [-0.05, 0.02, 0.0005, -0.0003, 0]}   # used only with lens_distortion\n"
    << "    baseline_mm: 30           # right camera along +x of the left one\n"
    << "    plate_gap_mm: 45          # both cameras below the plate's camera-side face\n"
    << "  fps: 30\n"
    << "robot:\n"
    << "  speed_mm_s: 6\n"
    << "  approach_speed_mm_s: 30\n"
    << "  press_depth_mm: 1.5\n"
    << "  safe_clearance_mm: 2\n"
    << "  max_contact_depth_mm: 10\n"
    << "# Add what a pipeline needs: elastic_spread, lens_distortion, render, pixel_noise,\n"
    << "# blur, marker_dropout, pose_noise (each opt-in; see sample_clouds/README.md).\n"
    << "effects: [contact, refraction]\n";
  return s.str();
}

void write_object(const fs::path& out_dir, const SampleObject& object) {
  const fs::path folder = out_dir / object.surface.name;
  fs::create_directories(folder);
  touchcloud::scoring::TriangleMesh mesh;
  const pcl::PolygonMesh polygons = height_field_mesh(object, mesh);
  if (pcl::io::savePLYFileBinary((folder / "mesh.ply").string(), polygons) < 0)
    throw std::runtime_error("cannot write " + (folder / "mesh.ply").string());

  // Ground truth from the mesh as written (float vertices), as a user's CAD
  // export would be sampled.
  const auto written = touchcloud::scoring::read_triangle_mesh(folder / "mesh.ply");
  const double area = touchcloud::scoring::surface_area_mm2(written);
  const auto count = static_cast<std::size_t>(std::lround(area * kGroundTruthPointsPerMm2));
  const auto points = touchcloud::scoring::sample_surface(written, count, kGroundTruthSeed, 1);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (const auto& p : points)
    cloud.push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
  if (pcl::io::savePCDFileBinary((folder / "ground_truth.pcd").string(), cloud) < 0)
    throw std::runtime_error("cannot write " + (folder / "ground_truth.pcd").string());
  std::ofstream(folder / "scene.yaml") << scene_yaml(object);

  // How far the mesh departs from the analytic surface (vertically), at random points.
  std::mt19937_64 rng(7);
  const auto& box = object.surface.footprint_mm;
  std::uniform_real_distribution<double> ux(box.min().x(), box.max().x()), uy(box.min().y(), box.max().y());
  double max_dev = 0, sum_dev = 0;
  const int probes = 20000;
  for (int i = 0; i < probes; ++i) {
    const double x = ux(rng), y = uy(rng);
    // Bilinear position in the grid cell, then the triangle's plane.
    const double fx = (x - box.min().x()) / object.mesh_step_mm, fy = (y - box.min().y()) / object.mesh_step_mm;
    const int ix = std::min(static_cast<int>(fx), static_cast<int>(std::lround(box.sizes().x() / object.mesh_step_mm)) - 1);
    const int iy = std::min(static_cast<int>(fy), static_cast<int>(std::lround(box.sizes().y() / object.mesh_step_mm)) - 1);
    const std::size_t cell = static_cast<std::size_t>(iy) * static_cast<std::size_t>(std::lround(box.sizes().x() / object.mesh_step_mm)) + ix;
    const auto& t1 = mesh.triangles[2 * cell];
    const auto& t2 = mesh.triangles[2 * cell + 1];
    double z = 0;
    for (const auto* t : {&t1, &t2}) {
      const Eigen::Vector3d a = mesh.vertices[(*t)[0]], b = mesh.vertices[(*t)[1]], c = mesh.vertices[(*t)[2]];
      const Eigen::Vector2d ab = (b - a).head<2>(), ac = (c - a).head<2>(), ap = Eigen::Vector2d(x, y) - a.head<2>();
      const double det = ab.x() * ac.y() - ab.y() * ac.x();
      const double u = (ap.x() * ac.y() - ap.y() * ac.x()) / det, v = (ab.x() * ap.y() - ab.y() * ap.x()) / det;
      if (u >= -1e-12 && v >= -1e-12 && u + v <= 1 + 1e-12) z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
    }
    const double dev = std::abs(z - object.surface.height_mm(x, y));
    max_dev = std::max(max_dev, dev);
    sum_dev += dev;
  }

  std::cout << object.surface.name << ": mesh " << mesh.vertices.size() << " vertices, " << mesh.triangles.size()
            << " triangles, " << area << " mm^2 (" << fs::file_size(folder / "mesh.ply") << " bytes); ground truth "
            << count << " points (" << fs::file_size(folder / "ground_truth.pcd") << " bytes); mesh vs analytic: mean "
            << sum_dev / probes << " mm, max " << max_dev << " mm\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_sample_objects OUT_DIR   (OUT_DIR: the repository's sample_clouds/)\n";
    return 2;
  }
  try {
    const fs::path out = argv[1];
    write_object(out, {touchcloud::simulation::wave_surface(), 1.0, 24, 6,
                       "The wave surface (200 x 50 mm) on the table, touched by the GelStereo Palm 2.0."});
    write_object(out, {touchcloud::simulation::fox_mask(), 2.0, 14, 14,
                       "The fox mask (120 x 120 mm relief) on the table, touched by the GelStereo Palm 2.0."});
  } catch (const std::exception& e) {
    std::cerr << "make_sample_objects: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
