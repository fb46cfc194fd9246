// touchcloud-make-scene MESH --name NAME [--scale S] [--out DIR] [--cell-mm C] [--sensor FAMILY]
// A user's object, one command from its mesh (STL, OBJ or PLY, any unit via
// --scale) to DIR/NAME/: the mesh as given, a scene that centres it on the
// table (its footprint around the origin, its bottom at z = 0) with a
// workspace and grid over its footprint. The scene is the ground truth too
// (the chamfer stage and `touchcloud score --gt` sample its object as
// placed, densely), so no sparser copy is written. Then it checks the object against the sensor: the size
// (a unit mistake), the gel's reach at every grid cell, and says what does
// not fit. Exit 0 (warnings on stderr), 2 bad input, 1 a failed write.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include <CLI/CLI.hpp>

#include "touchcloud/simulation/objects/object_surface.hpp"
#include "touchcloud/simulation/objects/reach_check.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/file_write.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"
#include "touchcloud/scoring/visible_surface.hpp"
#include "touchcloud/types/scene_object.hpp"
#include "touchcloud/types/workspace.hpp"

namespace fs = std::filesystem;
using namespace touchcloud;

namespace {

constexpr double kGelDiameterMm = 65.0;            // the GelStereo Palm 2.0 of the sample scenes

// Numbers as a person writes them: 65, 0.08, never 65.000000 or -0.
std::string num(double v) {
  std::ostringstream s;
  s << (v == 0 ? 0.0 : v);
  return s.str();
}

// The smallest cell (three significant digits, rounded up) that keeps a
// side of `side_mm` within kMaxGridCells cells.
double smallest_cell_mm(double side_mm) {
  const double cell = side_mm / kMaxGridCells;
  const double unit = std::pow(10.0, std::floor(std::log10(cell)) - 2);
  return std::ceil(cell / unit - 1e-9) * unit;
}

enum class SensorChoice { MarkerGelStereo, ColourGelStereo, GelSight };

struct Options {
  fs::path mesh, out = "sample_clouds";
  SensorChoice sensor = SensorChoice::MarkerGelStereo;
  std::string name;
  double scale = 1.0, cell_mm = 8.6;
};

// The `sensor:`, `robot:` and `effects:` sections of each family, as its
// shipped fox-mask scene has them (sample_clouds/fox_mask/scene*.yaml).
// The GelStereo Palm 2.0's gel, plate, cameras and robot, shared by both
// GelStereo gels; the colour-pattern gel adds its pattern after the markers.
#define TC_GELSTEREO_GEL                                                                   \
  "sensor:\n"                                                                               \
  "  gel: {diameter_mm: 65}\n"                                                              \
  "  markers: {min_spacing_mm: 1.5, mean_spacing_mm: 1.8, diameter_mm: 0.6, seed: 1}\n"
#define TC_GELSTEREO_OPTICS_ROBOT                                                                                  \
  "  plate: {thickness_mm: 5, tilt_deg: [0, 0], mu_air: 1.0, mu_acrylic: 1.49, mu_silicone: 1.41}\n"              \
  "  cameras:\n"                                                                                                   \
  "    left: {width_px: 1280, height_px: 720, fx_px: 651.5, fy_px: 652.0, cx_px: 598.6, cy_px: 377.1,\n"           \
  "           distortion: [-0.05, 0.02, 0.0005, -0.0003, 0]}\n"                                                    \
  "    baseline_mm: 30\n"                                                                                          \
  "    plate_gap_mm: 45\n"                                                                                         \
  "  fps: 30\n"                                                                                                    \
  "robot: {speed_mm_s: 6, approach_speed_mm_s: 30, press_depth_mm: 1.5, safe_clearance_mm: 2, max_contact_depth_mm: 10}\n"
const char* kMarkerGelStereo = TC_GELSTEREO_GEL TC_GELSTEREO_OPTICS_ROBOT "effects: [contact, refraction]\n";
const char* kColourGelStereo = TC_GELSTEREO_GEL
    "  pattern: colour_pattern\n"
    "  colour_pattern: {feature_mm: 1.0, opacity: 0.8, seed: 1, vignetting: 0.1, image_size_px: [640, 360]}\n"
    TC_GELSTEREO_OPTICS_ROBOT "effects: [contact, elastic_spread, refraction, render]\n";
#undef TC_GELSTEREO_GEL
#undef TC_GELSTEREO_OPTICS_ROBOT
const char* kGelSight =
    "sensor:\n"
    "  family: gelsight\n"
    "  name: gelsight_mini\n"
    "  image_size_px: [320, 240]\n"
    "  mm_per_px: 0.06             # a 19.2 x 14.4 mm flat pad\n"
    "  gel_thickness_mm: 2.5\n"
    "  lights:\n"
    "    - {direction: [0.8192, 0.0, 0.5736], colour_rgb: [110, 0, 0]}\n"
    "    - {direction: [-0.4096, 0.7094, 0.5736], colour_rgb: [0, 110, 0]}\n"
    "    - {direction: [-0.4096, -0.7094, 0.5736], colour_rgb: [0, 0, 110]}\n"
    "  reflectance: {diffuse: 1.0, specular: 0.15, shininess: 8}\n"
    "  ambient_rgb: [40, 40, 40]\n"
    "  vignetting: 0.1\n"
    "  fps: 25\n"
    "robot: {speed_mm_s: 3, approach_speed_mm_s: 10, press_depth_mm: 0.8, safe_clearance_mm: 2, max_contact_depth_mm: 2.5}\n"
    "effects: [contact, render]\n";

struct Family {
  const char* title;     // in the scene's first line
  const char* sections;  // sensor, robot, effects
  double contact_mm;     // the gel's extent: a dome's diameter, a flat pad's shorter side
  bool dome;             // a hemisphere lowered onto the object: the reach check applies
};
const std::map<SensorChoice, Family> kFamilies = {
    {SensorChoice::MarkerGelStereo, {"the marker GelStereo Palm 2.0", kMarkerGelStereo, kGelDiameterMm, true}},
    {SensorChoice::ColourGelStereo, {"the colour-pattern GelStereo", kColourGelStereo, kGelDiameterMm, true}},
    {SensorChoice::GelSight, {"a GelSight Mini-like monocular sensor", kGelSight, 14.4, false}},
};

std::string scene_yaml(const Options& o, const Eigen::Vector3d& shift, const Eigen::AlignedBox3d& placed, int gx, int gy) {
  const Family& family = kFamilies.at(o.sensor);
  std::ostringstream s;
  s << "# " << o.name << " (" << placed.sizes().x() << " x " << placed.sizes().y() << " x " << placed.sizes().z()
    << " mm) on the table, touched by " << family.title << ".\n"
    << "# Written by touchcloud-make-scene from " << o.mesh.filename().string() << "; edit freely.\n"
    << "name: " << o.name << "\n"
    << "object:\n"
    << "  mesh: " << o.mesh.filename().string() << "\n"
    << "  scale: " << o.scale << "              # mesh units to mm\n"
    << "  pose: {xyz_mm: [" << shift.x() << ", " << shift.y() << ", " << shift.z()
    << "], rpy_deg: [0, 0, 0]}   # footprint centred, bottom on the table\n"
    << "workspace:                  # base frame: the object's footprint, positions at cell centres\n"
    << "  x_mm: [" << placed.min().x() << ", " << placed.max().x() << "]\n"
    << "  y_mm: [" << placed.min().y() << ", " << placed.max().y() << "]\n"
    << "  grid: [" << gx << ", " << gy << "]\n"
    << family.sections;
  return s.str();
}

// What does not fit, one line each; empty when all does.
std::vector<std::string> check_fit(const ObjectSpec& spec, const scoring::TriangleMesh& mesh,
                                   const Eigen::AlignedBox3d& placed, int gx, int gy, const Family& family) {
  std::vector<std::string> problems;
  const Eigen::Vector3d size = placed.sizes();
  if (auto why = scoring::unit_mistake(mesh))
    problems.push_back(*why + (size.maxCoeff() < 5.0 ? " (--scale 1000 or 10)" : " (--scale 0.001)"));
  if (family.dome && size.x() < family.contact_mm && size.y() < family.contact_mm)
    problems.push_back("the footprint is smaller than the gel (" + num(family.contact_mm) +
                       " mm): every touch covers the whole object");
  if (!family.dome) return problems;  // a flat pad: no dome to stop on a wall
  const auto surface = simulation::make_object_surface(spec);
  const double r = 0.5 * kGelDiameterMm;
  WorkspaceGrid grid;
  grid.x_mm = Eigen::Vector2d(placed.min().x(), placed.max().x());
  grid.y_mm = Eigen::Vector2d(placed.min().y(), placed.max().y());
  grid.cells_x = gx;
  grid.cells_y = gy;
  const std::vector<double> gaps = simulation::apex_gaps_mm(*surface, grid, r);
  int unreachable = 0;
  std::ostringstream worst;
  double worst_gap = 0;
  for (int c = 0; c < grid.cells(); ++c) {
    const double gap = gaps[static_cast<std::size_t>(c)];
    if (gap <= simulation::kDefaultReachToleranceMm) continue;
    ++unreachable;
    if (gap > worst_gap) {
      worst_gap = gap;
      const Eigen::Vector2d at = grid.cell_centre_mm(c);
      worst.str("");
      worst << "(" << at.x() << ", " << at.y() << ") mm, where it stops " << gap << " mm above the surface";
    }
  }
  if (unreachable > 0)
    problems.push_back(std::to_string(unreachable) + " of " + std::to_string(gx * gy) +
                       " grid cells cannot be reached by the gel (a hole or a wall narrower than its " +
                       num(kGelDiameterMm) + " mm); the worst at " + worst.str() +
                       ": the planner leaves such cells out and the surface there is extrapolation");
  return problems;
}

int make_scene(const Options& o) {
  if (o.name.empty() || o.name.find_first_of("/\\.") != std::string::npos)
    throw InputError("--name '" + o.name + "': a folder name without '/', '\\' or '.'");
  const scoring::TriangleMesh raw = scoring::read_triangle_mesh(o.mesh);  // InputError naming the file
  Eigen::AlignedBox3d box;
  for (const auto& v : raw.vertices) box.extend(o.scale * v);
  // + 0.0 turns -0 into 0 in the scene file.
  const Eigen::Vector3d shift(-box.center().x() + 0.0, -box.center().y() + 0.0, -box.min().z() + 0.0);
  const Eigen::AlignedBox3d placed(box.min() + shift, box.max() + shift);
  // As a stage's `grid`: at most kMaxGridCells each way (the reach check
  // visits every cell).
  const double cells_x = std::max(1.0, std::ceil(placed.sizes().x() / o.cell_mm));
  const double cells_y = std::max(1.0, std::ceil(placed.sizes().y() / o.cell_mm));
  if (!(cells_x <= kMaxGridCells && cells_y <= kMaxGridCells))
    throw InputError("--cell-mm " + num(o.cell_mm) + ": a grid of " + num(cells_x) + " x " + num(cells_y) +
                     " cells over the " + num(placed.sizes().x()) + " x " + num(placed.sizes().y()) +
                     " mm footprint; the grid must be in [1, " + std::to_string(kMaxGridCells) +
                     "] cells each way (--cell-mm " + num(smallest_cell_mm(placed.sizes().head<2>().maxCoeff())) +
                     " or more)");
  const int gx = static_cast<int>(cells_x), gy = static_cast<int>(cells_y);

  const fs::path folder = o.out / o.name;
  ObjectSpec spec;
  spec.kind = ObjectKind::Mesh;
  spec.mesh = o.mesh;
  spec.scale = o.scale;
  spec.base_from_object = Eigen::Translation3d(shift);
  const scoring::TriangleMesh mesh = read_placed_object_mesh(spec);
  const double area = scoring::surface_area_mm2(mesh);
  if (!(area > 0)) throw InputError(o.mesh.string() + ": the mesh has no surface area");
  const std::vector<std::string> problems = check_fit(spec, mesh, placed, gx, gy, kFamilies.at(o.sensor));

  // Everything is computed before the first file is written.
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError("cannot create the output folder " + folder.string() + ": " + ec.message());
  const fs::path mesh_copy = folder / o.mesh.filename();
  if (fs::absolute(mesh_copy).lexically_normal() != fs::absolute(o.mesh).lexically_normal())
    fs::copy_file(o.mesh, mesh_copy, fs::copy_options::overwrite_existing);
  write_file(folder / "scene.yaml", scene_yaml(o, shift, placed, gx, gy));
  std::cout << "wrote " << folder.string() << "/: scene.yaml, " << o.mesh.filename().string() << "; object "
            << placed.sizes().x() << " x "
            << placed.sizes().y() << " x " << placed.sizes().z() << " mm, grid " << gx << " x " << gy << "\n";
  for (const auto& p : problems) std::cerr << "warning: " << p << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ignore_file_size_signal();  // a file-size limit fails a write as a full disk does
  CLI::App app{"From a mesh to a scene, which is also its ground truth: DIR/NAME/{scene.yaml, mesh}"};
  Options o;
  app.add_option("mesh", o.mesh, "the object's mesh (.stl, .obj, .ply with faces)")->required();
  app.add_option("--name", o.name, "the object's name: the folder and the scene's name")->required();
  app.add_option("--scale", o.scale, "mesh units to mm (1000 for a mesh in metres)")->check(CLI::PositiveNumber);
  app.add_option("--out", o.out, "where the object's folder goes (default: sample_clouds)");
  app.add_option("--sensor", o.sensor, "the sensor family the scene's sensor: section describes")
      ->transform(CLI::CheckedTransformer(std::map<std::string, SensorChoice>{
          {"marker_gelstereo", SensorChoice::MarkerGelStereo},
          {"colour_gelstereo", SensorChoice::ColourGelStereo},
          {"gelsight", SensorChoice::GelSight}}))
      ->default_str("marker_gelstereo");
  app.add_option("--cell-mm", o.cell_mm, "grid cell size over the footprint (default 8.6, the fox mask's)")
      ->check(CLI::PositiveNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return make_scene(o);
  } catch (const InputError& e) {
    std::cerr << "touchcloud-make-scene: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "touchcloud-make-scene: error: " << e.what() << "\n";
    return 1;
  }
}
