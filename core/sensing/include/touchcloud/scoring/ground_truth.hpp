// Ground truth for scoring: a point cloud as given, or points sampled
// uniformly by area from a CAD mesh. Also reads the estimates to score.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/scoring/nearest_point_index.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"
#include "touchcloud/scoring/visible_surface.hpp"

namespace touchcloud::scoring {

// Default mesh sampling: 100 points per mm^2 (a mean spacing of 0.1 mm), at
// least kMinMeshSamples and at most kMaxMeshSamples. docs/scoring.md derives
// the error this leaves in the metrics.
inline constexpr double kMeshSamplesPerMm2 = 100.0;
inline constexpr std::size_t kMinMeshSamples = 100'000;
inline constexpr std::size_t kMaxMeshSamples = 10'000'000;

// The default sample count for a mesh of this area.
std::size_t default_mesh_samples(double area_mm2);

enum class GroundTruthKind { Cloud, Mesh };
const char* to_string(GroundTruthKind kind);

struct GroundTruthOptions {
  std::size_t mesh_samples = 0;  // 0: default_mesh_samples(area)
  std::uint64_t seed = 0;        // mesh sampling
  NonFinitePoints nonfinite = NonFinitePoints::Refuse;  // clouds
  int threads = 0;               // 0: all
  // from_above: of a mesh's samples, only those a press from above can
  // reach (visible_from_above); a cloud is refused, having no surfaces.
  Visibility visible = Visibility::all;
  // With visible all, a mesh's samples are also flagged by whether a press
  // from above sees them (GroundTruth::seen_from_above), so the share of the
  // reachable surface covered can stand beside the share of the whole.
  bool flag_seen_from_above = false;
};

struct GroundTruth {
  std::filesystem::path file;
  GroundTruthKind kind = GroundTruthKind::Cloud;
  std::size_t dropped_nonfinite = 0;  // clouds
  double area_mm2 = 0;                // meshes
  std::size_t triangles = 0;          // meshes
  NearestPointIndex points;           // the points scored against, indexed
  Visibility visible = Visibility::all;
  std::size_t hidden_points = 0;      // samples dropped as not visible
  // Meshes scored whole, when asked (flag_seen_from_above): per indexed point,
  // in the index's order, whether a press from above sees it; empty otherwise
  // and when it sees every point (an open surface).
  std::vector<bool> seen_from_above{};

  // Mean spacing of the samples on a mesh, sqrt(area / samples drawn); 0 for clouds.
  double sample_spacing_mm() const;
};

// A ground-truth file read and checked, before the sampling and indexing
// that cost most of a load (0.3 s for the fox mask's 1.7 M samples): a
// pipeline checks the file when it loads and indexes it when it runs.
struct GroundTruthFile {
  std::filesystem::path file;
  GroundTruthKind kind = GroundTruthKind::Cloud;
  TriangleMesh mesh;                  // meshes
  double area_mm2 = 0;                // meshes; positive
  Points cloud;                       // clouds; not empty
  std::size_t dropped_nonfinite = 0;  // clouds
};

// Reads `file`: .stl, .obj and .ply with faces are meshes (to be sampled),
// .pcd and .ply without faces are clouds, .yaml and .yml are scenes (their
// object as read_scene_ground_truth places it). Throws InputError naming the
// file, also for a mesh with no surface area.
GroundTruthFile read_ground_truth(const std::filesystem::path& file, const GroundTruthOptions& options = {});
// The object of a scene file as ground truth: its mesh scaled and posed as
// the simulator places it, so a simulated run cannot be scored against an
// object it did not touch. InputError naming the scene when its object is an
// analytic surface (give a ground-truth file for those) or the mesh is bad.
GroundTruthFile read_scene_ground_truth(const std::filesystem::path& scene_file);
// Samples a mesh (options.mesh_samples, seed), keeps the visible samples
// (options.visible) and indexes the points.
GroundTruth index_ground_truth(GroundTruthFile file, const GroundTruthOptions& options = {});
// Both of the above.
GroundTruth load_ground_truth(const std::filesystem::path& file, const GroundTruthOptions& options = {});

struct Estimate {
  Points points;
  std::size_t dropped_nonfinite = 0;
};
// Reads an estimated cloud (.pcd or .ply); InputError when it is unreadable
// or empty.
Estimate read_estimate(const std::filesystem::path& file, NonFinitePoints nonfinite = NonFinitePoints::Refuse);

}  // namespace touchcloud::scoring
