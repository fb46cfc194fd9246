// The upper surface of a triangle mesh: at each (x, y) the highest triangle
// above it, found through a uniform grid of the triangles' xy footprints.
// Exact to the mesh (no resampling); the table (z = 0) where no triangle is.
#pragma once

#include <array>
#include <vector>

#include "touchcloud/simulation/objects/object_surface.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::simulation {

class MeshSurface final : public ObjectSurface {
 public:
  // `mesh` already in the base frame. Triangles seen edge-on from above
  // (vertical walls) are left out: their neighbours bound the same heights.
  explicit MeshSurface(const scoring::TriangleMesh& mesh);

  double height_mm(const Eigen::Vector2d& xy_mm) const override;
  double max_height_mm(const Eigen::Vector2d& centre_mm, double radius_mm) const override;
  // Above its cell's highest vertex, a point is clear of every triangle
  // there: no triangle is read.
  double overlap_mm(const Eigen::Vector2d& xy_mm, double z_mm) const override;
  std::size_t triangles() const { return triangles_.size(); }

 private:
  struct Triangle {
    Eigen::Vector2d a, ab, ac;  // xy corner and edges
    double za, zab, zac;        // z at a and its change along the edges
    double inv_det;
  };
  int cell_index(int ix, int iy) const { return iy * nx_ + ix; }
  void cell_of(const Eigen::Vector2d& xy, int& ix, int& iy) const;
  // The cell holding xy; -1 outside the grid, where there is no triangle.
  int cell_at(const Eigen::Vector2d& xy) const;
  double height_in_cell(const Eigen::Vector2d& xy, int cell) const;

  std::vector<Triangle> triangles_;
  Eigen::Vector2d origin_;
  double cell_mm_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cell_start_, cell_triangles_;  // CSR lists per cell
  std::vector<double> cell_max_z_;                          // highest vertex over each cell
};

}  // namespace touchcloud::simulation
