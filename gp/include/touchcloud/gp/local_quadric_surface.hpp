// A signed distance from local quadrics of the touched points, for surfaces
// a single smooth field rounds off: a thin wall touched on one face only
// near a point, which a GP's long lengthscale (chosen for the gaps between
// touches) thickens, since its field cannot turn round within the wall.
//
// One patch per `patch_spacing_mm` cube of touched points: a quadric height
// over its tangent plane, fitted by least squares to the touched points within
// `fit_radius_mm` whose normals lie within `fit_normal_deg` of the patch's (so
// a patch on one face of a wall never takes points of the other). Normals are
// each point's neighbourhood plane (its `normal_neighbours` nearest), turned
// to the side its touch came from. A query point takes the distance, along
// the patch's normal, to the quadric of the patch within `reach_mm` (across
// the normal) that minimises |distance| + `lateral_weight` * lateral distance:
// the nearest surface a patch extrapolates, preferring near patches. So a
// point in a cup's hollow beside a touched outer wall takes the inner wall's
// curve from a patch further along it. Where no patch reaches, the surface
// says nothing (covered() is false) and the caller falls back (gpis_surface:
// the GP's mean).
//
// Sharp edges (`edge_deg` > 0): beside an edge the nearest patch's quadric
// runs on past it, so a low face's plane, carried under the riser of a step,
// puts a sheet inside the solid. Where the best patch and the best of those
// turned more than `edge_deg` from it disagree in sign, the two are combined
// as the solid they bound: each centre behind the other's plane is a convex
// edge (the solid is inside both: the larger distance), each in front a
// concave one (inside either: the smaller); otherwise the best stands. A thin
// wall's two faces are a convex pair, so its hollow stays outside.
//
// Free space: the gel that made a touch lay against its patch, so what lies
// in front of a patch (more than `free_margin_mm` outside its quadric, within
// `free_radius_mm` of its centre across the normal and `free_depth_mm` along
// it) holds no surface; in_free_space() says so, and gpis_surface drops mesh
// triangles there. A gel pressed into a concave corner (a cup's wall
// where it meets the floor) lay against both faces, and the cylinder in
// front of one patch runs into the other: with `free_support_mm` > 0 a point
// that lies on a patch's quadric (within `free_margin_mm`, within
// `free_support_mm` of its centre across its normal) is touched surface and
// never free space.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace touchcloud::gp {

struct LocalQuadricOptions {
  double patch_spacing_mm = 3.0;
  double fit_radius_mm = 7.0;
  double fit_normal_deg = 30.0;
  int normal_neighbours = 20;
  int min_fit_points = 15;  // fewer: the patch is the plane through its points
  double reach_mm = 16.0;
  double lateral_weight = 0.3;
  double edge_deg = 0.0;  // 0: no edge combination
  double free_radius_mm = 7.0;
  double free_margin_mm = 1.0;
  double free_depth_mm = 25.0;
  double free_support_mm = 0.0;  // 0: a patch's support does not count
  void validate() const;  // InputError naming the field, its value and the rule
};

class LocalQuadricSurface {
 public:
  // `points_mm`: the touched points, base frame; `outward`: for each, a
  // vector pointing out of the object (the palm's normal of its touch), which
  // only orients the point's fitted normal. InputError on no points,
  // mismatched rows or anything not finite.
  LocalQuadricSurface(const Eigen::MatrixX3d& points_mm, const Eigen::MatrixX3d& outward, LocalQuadricOptions options = {});
  LocalQuadricSurface(LocalQuadricSurface&&) noexcept;
  LocalQuadricSurface& operator=(LocalQuadricSurface&&) noexcept;
  ~LocalQuadricSurface();

  std::size_t patches() const;
  // Signed distance at each query (positive outside) where covered(), else 0;
  // `covered` gets one flag per query. Runs on up to `threads` threads
  // (0: one per core); the values do not depend on the count.
  Eigen::VectorXd value(const Eigen::Ref<const Eigen::MatrixX3d>& q, std::vector<bool>& covered, int threads = 0) const;
  bool in_free_space(const Eigen::Vector3d& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace touchcloud::gp
