#include "touchcloud/simulation/objects/mesh_surface.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/error.hpp"

namespace touchcloud::simulation {

namespace {
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
// Points on a shared edge belong to both triangles: rounding must not open gaps.
constexpr double kInsideTolerance = 1e-12;
// Above a cell's highest corner by this much, a point is above every height there.
constexpr double kBoundSlackMm = 1e-6;
}  // namespace

MeshSurface::MeshSurface(const scoring::TriangleMesh& mesh) {
  Eigen::AlignedBox2d box;
  std::vector<double> top_z;
  triangles_.reserve(mesh.triangles.size());
  top_z.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    Triangle tri;
    tri.a = a.head<2>();
    tri.ab = (b - a).head<2>();
    tri.ac = (c - a).head<2>();
    const double det = cross(tri.ab, tri.ac);
    if (!(std::abs(det) > 1e-12 * tri.ab.norm() * tri.ac.norm())) continue;  // edge-on from above
    tri.za = a.z();
    tri.zab = b.z() - a.z();
    tri.zac = c.z() - a.z();
    tri.inv_det = 1.0 / det;
    triangles_.push_back(tri);
    top_z.push_back(std::max({a.z(), b.z(), c.z()}));
    box.extend(a.head<2>());
    box.extend(b.head<2>());
    box.extend(c.head<2>());
  }
  if (triangles_.empty()) throw InputError("the mesh has no triangle that faces up or down (all are edge-on from above)");

  // About two triangles per cell.
  const Eigen::Vector2d size = box.sizes().cwiseMax(1e-6);
  cell_mm_ = std::max(std::sqrt(2.0 * size.prod() / static_cast<double>(triangles_.size())), 1e-3);
  nx_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_mm_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_mm_)));
  origin_ = box.min();

  // Each cell's triangles in their order, as compressed rows: counted, then
  // placed (one allocation, not a list per cell: an approach view builds
  // one of these for every candidate touch).
  const std::size_t cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  std::vector<std::array<int, 4>> spans(triangles_.size());  // x0, y0, x1, y1
  cell_start_.assign(cells + 1, 0);
  cell_max_z_.assign(cells, 0.0);
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& t = triangles_[i];
    Eigen::AlignedBox2d tb(t.a);
    tb.extend(t.a + t.ab);
    tb.extend(t.a + t.ac);
    auto& [x0, y0, x1, y1] = spans[i];
    cell_of(tb.min(), x0, y0);
    cell_of(tb.max(), x1, y1);
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        ++cell_start_[static_cast<std::size_t>(cell_index(ix, iy)) + 1];
        cell_max_z_[cell_index(ix, iy)] = std::max(cell_max_z_[cell_index(ix, iy)], top_z[i]);
      }
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_triangles_.resize(cell_start_.back());
  std::vector<std::uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const auto& [x0, y0, x1, y1] = spans[i];
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) cell_triangles_[next[cell_index(ix, iy)]++] = static_cast<std::uint32_t>(i);
  }
}

void MeshSurface::cell_of(const Eigen::Vector2d& xy, int& ix, int& iy) const {
  ix = std::clamp(static_cast<int>(std::floor((xy.x() - origin_.x()) / cell_mm_)), 0, nx_ - 1);
  iy = std::clamp(static_cast<int>(std::floor((xy.y() - origin_.y()) / cell_mm_)), 0, ny_ - 1);
}

int MeshSurface::cell_at(const Eigen::Vector2d& xy) const {
  const Eigen::Vector2d rel = xy - origin_;
  const double fx = rel.x() / cell_mm_, fy = rel.y() / cell_mm_;
  // Outside the grid (with a rounding margin) there is no triangle.
  if (!(fx >= -1e-9 && fy >= -1e-9 && fx <= nx_ + 1e-9 && fy <= ny_ + 1e-9)) return -1;
  int ix, iy;
  cell_of(xy, ix, iy);
  return cell_index(ix, iy);
}

double MeshSurface::height_in_cell(const Eigen::Vector2d& xy, int cell) const {
  double top = 0.0;  // the table
  for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
    const Triangle& t = triangles_[cell_triangles_[k]];
    const Eigen::Vector2d p = xy - t.a;
    const double u = cross(p, t.ac) * t.inv_det;
    const double v = cross(t.ab, p) * t.inv_det;
    if (u < -kInsideTolerance || v < -kInsideTolerance || u + v > 1 + kInsideTolerance) continue;
    top = std::max(top, t.za + u * t.zab + v * t.zac);
  }
  return top;
}

double MeshSurface::height_mm(const Eigen::Vector2d& xy) const {
  const int cell = cell_at(xy);
  return cell < 0 ? 0.0 : height_in_cell(xy, cell);
}

double MeshSurface::overlap_mm(const Eigen::Vector2d& xy, double z) const {
  const int cell = cell_at(xy);
  if (cell < 0) return -z;
  // A height is a weighted mean of a triangle's corners, with weights down
  // to -kInsideTolerance, so it exceeds the highest corner by at most ~1e-12
  // of the triangle's rise; the slack covers that and rounding.
  const double bound = cell_max_z_[cell] + kBoundSlackMm;
  if (z > bound) return bound - z;
  return height_in_cell(xy, cell) - z;
}

double MeshSurface::max_height_mm(const Eigen::Vector2d& centre, double radius) const {
  int x0, y0, x1, y1;
  cell_of(centre.array() - radius, x0, y0);
  cell_of(centre.array() + radius, x1, y1);
  double top = 0.0;
  for (int iy = y0; iy <= y1; ++iy)
    for (int ix = x0; ix <= x1; ++ix) top = std::max(top, cell_max_z_[cell_index(ix, iy)]);
  return top;
}

}  // namespace touchcloud::simulation
