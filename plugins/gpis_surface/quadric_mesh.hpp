// gpis_surface's `surface: local_quadrics`: the meshed field is the local
// quadrics' signed distance (touchcloud/gp/local_quadric_surface.hpp) where a
// patch reaches and the GP's mean elsewhere. Where that field jumps (from one
// patch's distance to another's, or to the GP's) the level set would put a
// sheet that no patch supports, so a triangle whose centroid's field lies
// more than half a grid cell from zero is dropped, and so is one in the
// space a touch's gel lay in.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/gp/level_set_mesh.hpp"
#include "touchcloud/gp/local_quadric_surface.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud {

struct QuadricMeshCounts {
  std::size_t jumps = 0;       // triangles dropped on a jump of the field
  std::size_t free_space = 0;  // triangles dropped in a gel's space
  std::vector<Eigen::Vector3d> jump_centroids;  // with keep_jumps: the centroid of each triangle dropped on a jump
};

// `gp_mean`: the GP's mean at points (the values on the grid where no patch
// reaches). `table_z_mm`: the table clips the field as gp::clip_above_table.
// `keep_jumps`: the dropped jumps' centroids are kept in `counts` (where a
// face is not yet found: gpis_surface's plan_gaps).
scoring::TriangleMesh local_quadric_mesh(const gp::SampleGrid& grid, const gp::LocalQuadricSurface& quadrics,
                                         const std::function<Eigen::VectorXd(const Eigen::MatrixX3d&)>& gp_mean,
                                         std::optional<double> table_z_mm, int threads, QuadricMeshCounts& counts,
                                         bool keep_jumps = false);

}  // namespace touchcloud
