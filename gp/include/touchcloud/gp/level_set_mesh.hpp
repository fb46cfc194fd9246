// The zero level set of a function sampled on a regular grid, as a triangle
// mesh, by VTK's flying edges (vtkFlyingEdges3D). Only this part of the gp
// library links VTK (target touchcloud_gp_level_set).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::gp {

// A regular grid: `points` samples per axis from `origin_mm` at `spacing_mm`;
// samples are laid out x fastest, then y, then z.
struct SampleGrid {
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();
  double spacing_mm = 1.0;
  Eigen::Vector3i points = Eigen::Vector3i::Constant(2);
  Eigen::Index size() const { return Eigen::Index{points.x()} * points.y() * points.z(); }
  Eigen::MatrixX3d sample_points() const;
};

// The bounding box of `points` grown by `margin_mm` on every side, with
// `cells` cells along its longest side. InputError for no points, a
// non-positive margin or fewer than 2 cells.
SampleGrid grid_around(const Eigen::MatrixX3d& points_mm, double margin_mm, int cells);

// The same box, reaching `margin_mm` below a table at z = `table_z_mm` too,
// and the table's plane midway between two layers of samples (so that
// clip_above_table's cap crosses grid edges, never lies on samples).
SampleGrid grid_around(const Eigen::MatrixX3d& points_mm, double margin_mm, int cells, double table_z_mm);

// An object resting on a table: a signed distance (positive outside)
// sampled on `grid` becomes its max with the height below the plane z =
// `table_z_mm`, the intersection of its inside with the space above the
// table. Its zero level set then lies on or above the plane, closed by the
// plane where the inside reaches it: the face the object stands on, which no
// touch can reach. InputError for a value count that does not match.
void clip_above_table(const SampleGrid& grid, double table_z_mm, Eigen::VectorXd& values);

// The surface where `values` (one per grid sample) cross 0; the triangles
// share their vertices and face the positive side. A level set that stays
// inside the grid is closed. InputError for a value count that does not
// match, or a value that is not finite; an empty mesh when nothing crosses.
scoring::TriangleMesh zero_level_set(const SampleGrid& grid, const Eigen::VectorXd& values);

// The triangles of `mesh` whose `keep` is true (one flag per triangle), in
// their order, with the vertices they use, in the order of first use.
scoring::TriangleMesh kept_triangles(const scoring::TriangleMesh& mesh, const std::vector<bool>& keep);

// Drops each connected piece of `mesh` (triangles joined through shared
// vertices) none of whose vertices lies within `support_mm` of a row of
// `support` (the touched points): a piece the smooth field alone put far
// from every touch, a bubble of the GP's mean. Returns the triangles
// dropped; the rest keep their order. InputError for no support points, a
// support_mm that is not finite and > 0, or a point that is not finite.
std::size_t drop_unsupported_pieces(scoring::TriangleMesh& mesh, const Eigen::MatrixX3d& support, double support_mm);

}  // namespace touchcloud::gp
