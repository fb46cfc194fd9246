#include "touchcloud/scoring/visible_surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

namespace touchcloud::scoring {

const char* to_string(Visibility visibility) { return visibility == Visibility::from_above ? "from_above" : "all"; }

namespace {

// A triangle projected on x-y, with what it takes to find its height at a point.
struct Projected {
  Eigen::Vector2d a, e1, e2;  // corner and edges in x-y
  Eigen::Vector3d z;          // heights of the corners
  double det;                 // of [e1 e2]; ~0 for a wall seen edge-on
};

// Below this a surface coincides with the point (rounding of a point
// sampled on the triangle itself, or on a crease it shares).
constexpr double kAboveMm = 1e-4;
// A point on a triangle's projected edge is inside it: a vertical wall's
// samples lie under the edge of the face above them, which hides them as a
// z-buffer would.
constexpr double kOnEdge = 1e-9;

}  // namespace

std::vector<bool> seen_from_above(const TriangleMesh& mesh, const Points& points) {
  Eigen::AlignedBox2d box;
  for (const auto& v : mesh.vertices) box.extend(v.head<2>());
  std::vector<Projected> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& p0 = mesh.vertices[t[0]];
    const Eigen::Vector3d& p1 = mesh.vertices[t[1]];
    const Eigen::Vector3d& p2 = mesh.vertices[t[2]];
    Projected q{p0.head<2>(), (p1 - p0).head<2>(), (p2 - p0).head<2>(), {p0.z(), p1.z(), p2.z()}, 0};
    q.det = q.e1.x() * q.e2.y() - q.e1.y() * q.e2.x();
    const double scale = q.e1.squaredNorm() + q.e2.squaredNorm();
    if (std::abs(q.det) > 1e-12 * scale) triangles.push_back(q);
  }
  // About one triangle per cell, at most 2048 cells each way.
  const Eigen::Vector2d size = box.sizes().cwiseMax(1e-9);
  const double cell = std::max(std::sqrt(size.x() * size.y() / std::max<std::size_t>(1, triangles.size())),
                               std::max(size.x(), size.y()) / 2048.0);
  const int nx = std::max(1, static_cast<int>(std::ceil(size.x() / cell)));
  const int ny = std::max(1, static_cast<int>(std::ceil(size.y() / cell)));
  const auto cell_of = [&](double v, double lo, int n) {
    return std::clamp(static_cast<int>(std::floor((v - lo) / cell)), 0, n - 1);
  };
  std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(nx) * ny);
  for (std::uint32_t i = 0; i < triangles.size(); ++i) {
    const Projected& q = triangles[i];
    Eigen::AlignedBox2d b(q.a);
    b.extend(q.a + q.e1);
    b.extend(q.a + q.e2);
    for (int y = cell_of(b.min().y(), box.min().y(), ny); y <= cell_of(b.max().y(), box.min().y(), ny); ++y)
      for (int x = cell_of(b.min().x(), box.min().x(), nx); x <= cell_of(b.max().x(), box.min().x(), nx); ++x)
        bins[static_cast<std::size_t>(y) * nx + x].push_back(i);
  }
  std::vector<bool> seen(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector3d& p = points[k];
    // A point a rounding step outside the box is in its edge bin (clamped),
    // with the triangles whose edge it lies on.
    bool hidden = false;
    const auto& bin =
        bins[static_cast<std::size_t>(cell_of(p.y(), box.min().y(), ny)) * nx + cell_of(p.x(), box.min().x(), nx)];
    for (std::uint32_t i : bin) {
      const Projected& q = triangles[i];
      const Eigen::Vector2d d = p.head<2>() - q.a;
      const double u = (d.x() * q.e2.y() - d.y() * q.e2.x()) / q.det;
      const double v = (q.e1.x() * d.y() - q.e1.y() * d.x()) / q.det;
      if (u < -kOnEdge || v < -kOnEdge || u + v > 1 + kOnEdge) continue;
      const double z = q.z[0] + u * (q.z[1] - q.z[0]) + v * (q.z[2] - q.z[0]);
      if (z > p.z() + kAboveMm) {
        hidden = true;
        break;
      }
    }
    seen[k] = !hidden;
  }
  return seen;
}

Points visible_from_above(const TriangleMesh& mesh, const Points& points) {
  const std::vector<bool> seen = seen_from_above(mesh, points);
  Points visible;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (seen[k]) visible.push_back(points[k]);
  return visible;
}

std::optional<std::string> unit_mistake(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v);
  const double largest = box.sizes().maxCoeff();
  std::ostringstream s;
  s << "the object is " << (largest < 5.0 ? "only " : "") << largest << " mm across: ";
  if (largest < 5.0) return s.str() + "is the mesh in metres or centimetres?";
  if (largest > 2000.0) return s.str() + "is the mesh in micrometres?";
  return std::nullopt;
}

}  // namespace touchcloud::scoring
