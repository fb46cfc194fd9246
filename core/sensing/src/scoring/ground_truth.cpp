#include "touchcloud/scoring/ground_truth.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/error.hpp"
#include "touchcloud/types/scene_object.hpp"

namespace touchcloud::scoring {

std::size_t default_mesh_samples(double area_mm2) {
  const double wanted = std::ceil(area_mm2 * kMeshSamplesPerMm2);
  if (!(wanted < static_cast<double>(kMaxMeshSamples))) return kMaxMeshSamples;
  return std::max(kMinMeshSamples, static_cast<std::size_t>(wanted));
}

const char* to_string(GroundTruthKind kind) { return kind == GroundTruthKind::Mesh ? "mesh" : "cloud"; }

double GroundTruth::sample_spacing_mm() const {
  return kind == GroundTruthKind::Mesh ? std::sqrt(area_mm2 / static_cast<double>(points.size() + hidden_points))
                                       : 0.0;
}

GroundTruthFile read_ground_truth(const std::filesystem::path& file, const GroundTruthOptions& options) {
  const std::string ext = file.extension().string();
  if (ext == ".yaml" || ext == ".yml" || ext == ".YAML" || ext == ".YML") return read_scene_ground_truth(file);
  GroundTruthFile out;
  out.file = file;
  if (is_mesh_file(file)) {
    out.kind = GroundTruthKind::Mesh;
    out.mesh = read_triangle_mesh(file);
    out.area_mm2 = surface_area_mm2(out.mesh);
    if (!(out.area_mm2 > 0) || !std::isfinite(out.area_mm2))
      throw InputError(file.string() + ": the mesh has no surface area to sample (" +
                       std::to_string(out.mesh.triangles.size()) + " triangles, all degenerate)");
    return out;
  }
  CloudFile cloud = read_cloud_file(file, options.nonfinite);
  out.cloud = to_points(*cloud.cloud);
  out.dropped_nonfinite = cloud.dropped_nonfinite;
  return out;
}

GroundTruthFile read_scene_ground_truth(const std::filesystem::path& scene_file) {
  const ObjectSpec object = load_scene_object(scene_file);
  if (object.kind != ObjectKind::Mesh)
    throw InputError("scene file " + scene_file.string() + ": its object is the analytic surface '" +
                         to_string(object.kind) + "'; score it against a ground-truth file instead",
                     object.where);
  GroundTruthFile out;
  out.file = object.mesh;
  out.kind = GroundTruthKind::Mesh;
  out.mesh = read_placed_object_mesh(object);
  out.area_mm2 = surface_area_mm2(out.mesh);
  if (!(out.area_mm2 > 0) || !std::isfinite(out.area_mm2))
    throw InputError(object.mesh.string() + ": the mesh has no surface area to sample", object.where);
  return out;
}

GroundTruth index_ground_truth(GroundTruthFile file, const GroundTruthOptions& options) {
  if (file.kind == GroundTruthKind::Cloud && options.visible != Visibility::all)
    throw InputError(file.file.string() + ": a cloud has no surfaces to hide one another; visible " +
                     to_string(options.visible) + " needs a mesh or a scene");
  if (file.kind == GroundTruthKind::Cloud)
    return GroundTruth{file.file, GroundTruthKind::Cloud, file.dropped_nonfinite, 0.0, 0,
                       NearestPointIndex(std::move(file.cloud), options.threads)};
  const std::size_t count = options.mesh_samples > 0 ? options.mesh_samples : default_mesh_samples(file.area_mm2);
  Points samples;
  try {
    samples = sample_surface(file.mesh, count, options.seed, options.threads);
  } catch (const InputError& e) {
    throw InputError(file.file.string() + ": " + e.what());
  }
  std::size_t hidden = 0;
  if (options.visible == Visibility::from_above) {
    Points seen = visible_from_above(file.mesh, samples);
    hidden = samples.size() - seen.size();
    samples = std::move(seen);
    if (samples.empty()) throw InputError(file.file.string() + ": no sample of the mesh is visible from above");
  }
  GroundTruth gt{file.file, GroundTruthKind::Mesh, 0, file.area_mm2, file.mesh.triangles.size(),
                 NearestPointIndex(std::move(samples), options.threads), options.visible, hidden};
  if (options.flag_seen_from_above && options.visible == Visibility::all) {
    gt.seen_from_above = seen_from_above(file.mesh, gt.points.points());
    // An open surface seen whole from above has nothing hidden to tell apart.
    if (std::find(gt.seen_from_above.begin(), gt.seen_from_above.end(), false) == gt.seen_from_above.end())
      gt.seen_from_above.clear();
  }
  return gt;
}

GroundTruth load_ground_truth(const std::filesystem::path& file, const GroundTruthOptions& options) {
  return index_ground_truth(read_ground_truth(file, options), options);
}

Estimate read_estimate(const std::filesystem::path& file, NonFinitePoints nonfinite) {
  CloudFile cloud = read_cloud_file(file, nonfinite);
  return {to_points(*cloud.cloud), cloud.dropped_nonfinite};
}

}  // namespace touchcloud::scoring
