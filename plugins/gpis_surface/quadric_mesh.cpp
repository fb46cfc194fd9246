#include "quadric_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace touchcloud {

namespace {

// The field meshed: the quadrics' distance where covered, the GP's mean
// elsewhere, clipped by the table.
Eigen::VectorXd field_at(const Eigen::MatrixX3d& points, const gp::LocalQuadricSurface& quadrics,
                         const std::function<Eigen::VectorXd(const Eigen::MatrixX3d&)>& gp_mean,
                         std::optional<double> table_z_mm, int threads) {
  std::vector<bool> covered;
  Eigen::VectorXd values = quadrics.value(points, covered, threads);
  std::vector<Eigen::Index> rest;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (!covered[static_cast<std::size_t>(i)]) rest.push_back(i);
  if (!rest.empty()) {
    Eigen::MatrixX3d far(static_cast<Eigen::Index>(rest.size()), 3);
    for (std::size_t j = 0; j < rest.size(); ++j) far.row(static_cast<Eigen::Index>(j)) = points.row(rest[j]);
    const Eigen::VectorXd mean = gp_mean(far);
    for (std::size_t j = 0; j < rest.size(); ++j) values[rest[j]] = mean[static_cast<Eigen::Index>(j)];
  }
  if (table_z_mm)
    for (Eigen::Index i = 0; i < points.rows(); ++i) values[i] = std::max(values[i], *table_z_mm - points(i, 2));
  return values;
}

}  // namespace

scoring::TriangleMesh local_quadric_mesh(const gp::SampleGrid& grid, const gp::LocalQuadricSurface& quadrics,
                                         const std::function<Eigen::VectorXd(const Eigen::MatrixX3d&)>& gp_mean,
                                         std::optional<double> table_z_mm, int threads, QuadricMeshCounts& counts,
                                         bool keep_jumps) {
  Eigen::VectorXd values = field_at(grid.sample_points(), quadrics, gp_mean, std::nullopt, threads);
  if (table_z_mm) gp::clip_above_table(grid, *table_z_mm, values);
  const scoring::TriangleMesh all = gp::zero_level_set(grid, values);

  Eigen::MatrixX3d centroids(static_cast<Eigen::Index>(all.triangles.size()), 3);
  for (std::size_t t = 0; t < all.triangles.size(); ++t) {
    const auto& tri = all.triangles[t];
    centroids.row(static_cast<Eigen::Index>(t)) =
        ((all.vertices[tri[0]] + all.vertices[tri[1]] + all.vertices[tri[2]]) / 3.0).transpose();
  }
  const Eigen::VectorXd at_centroid = field_at(centroids, quadrics, gp_mean, table_z_mm, threads);
  const double jump_mm = 0.5 * grid.spacing_mm;

  std::vector<bool> keep(all.triangles.size(), false);
  counts = {};
  for (std::size_t t = 0; t < all.triangles.size(); ++t) {
    if (std::abs(at_centroid[static_cast<Eigen::Index>(t)]) > jump_mm) {
      ++counts.jumps;
      if (keep_jumps) counts.jump_centroids.push_back(centroids.row(static_cast<Eigen::Index>(t)).transpose());
      continue;
    }
    if (quadrics.in_free_space(centroids.row(static_cast<Eigen::Index>(t)).transpose())) {
      ++counts.free_space;
      continue;
    }
    keep[t] = true;
  }
  return gp::kept_triangles(all, keep);
}

}  // namespace touchcloud
