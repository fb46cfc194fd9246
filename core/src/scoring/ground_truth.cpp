#include "touchcloud/scoring/ground_truth.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/error.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::scoring {

std::size_t default_mesh_samples(double area_mm2) {
  const double wanted = std::ceil(area_mm2 * kMeshSamplesPerMm2);
  if (!(wanted < static_cast<double>(kMaxMeshSamples))) return kMaxMeshSamples;
  return std::max(kMinMeshSamples, static_cast<std::size_t>(wanted));
}

const char* to_string(GroundTruthKind kind) { return kind == GroundTruthKind::Mesh ? "mesh" : "cloud"; }

double GroundTruth::sample_spacing_mm() const {
  return kind == GroundTruthKind::Mesh ? std::sqrt(area_mm2 / static_cast<double>(points.size())) : 0.0;
}

GroundTruth load_ground_truth(const std::filesystem::path& file, const GroundTruthOptions& options) {
  if (is_mesh_file(file)) {
    const TriangleMesh mesh = read_triangle_mesh(file);
    const double area = surface_area_mm2(mesh);
    const std::size_t count = options.mesh_samples > 0 ? options.mesh_samples : default_mesh_samples(area);
    Points samples;
    try {
      samples = sample_surface(mesh, count, options.seed, options.threads);
    } catch (const InputError& e) {
      throw InputError(file.string() + ": " + e.what());
    }
    GroundTruth gt{file, GroundTruthKind::Mesh, 0, area, mesh.triangles.size(),
                   NearestPointIndex(std::move(samples), options.threads)};
    return gt;
  }
  CloudFile cloud = read_cloud_file(file, options.nonfinite);
  return GroundTruth{file, GroundTruthKind::Cloud, cloud.dropped_nonfinite, 0.0, 0,
                     NearestPointIndex(to_points(*cloud.cloud), options.threads)};
}

Estimate read_estimate(const std::filesystem::path& file, NonFinitePoints nonfinite) {
  CloudFile cloud = read_cloud_file(file, nonfinite);
  return {to_points(*cloud.cloud), cloud.dropped_nonfinite};
}

}  // namespace touchcloud::scoring
