#include "touchcloud/simulation/objects/approach_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "touchcloud/error.hpp"

namespace touchcloud::simulation {

namespace {
// A table seen closer to edge-on than this (the press direction's cosine
// with the table's normal) is not faced by the press.
constexpr double kFacingCosine = 1e-6;
}  // namespace

ApproachView::ApproachView(const scoring::TriangleMesh& object_mm, const Eigen::Isometry3d& press_from_object)
    : ApproachView(object_mm, press_from_object, std::numeric_limits<double>::infinity()) {}

ApproachView::ApproachView(const scoring::TriangleMesh& object_mm, const Eigen::Isometry3d& press_from_object,
                           double within_mm) {
  scoring::TriangleMesh moved = object_mm;
  double lowest = std::numeric_limits<double>::infinity();
  for (auto& v : moved.vertices) {
    v = press_from_object * v;
    lowest = std::min(lowest, v.z());
  }
  lift_mm_ = 1.0 - lowest;
  for (auto& v : moved.vertices) v.z() += lift_mm_;
  if (!std::isfinite(within_mm)) {
    object_ = std::make_unique<MeshSurface>(moved);
  } else {
    // A triangle that covers a point of the disc has its footprint's box
    // there; one whose box stays farther is never read.
    const auto far = [&](const std::array<std::uint32_t, 3>& t) {
      Eigen::AlignedBox2d box(moved.vertices[t[0]].head<2>());
      box.extend(moved.vertices[t[1]].head<2>());
      box.extend(moved.vertices[t[2]].head<2>());
      return box.squaredExteriorDistance(Eigen::Vector2d::Zero()) > within_mm * within_mm;
    };
    moved.triangles.erase(std::remove_if(moved.triangles.begin(), moved.triangles.end(), far), moved.triangles.end());
    if (!moved.triangles.empty()) {
      try {
        object_ = std::make_unique<MeshSurface>(moved);
      } catch (const InputError&) {
        // Near the axis only triangles edge-on to the press: nothing faces it there.
      }
    }
  }
  // z_object = row 2 of object_from_press applied to p.
  const Eigen::Isometry3d object_from_press = press_from_object.inverse();
  table_normal_ = object_from_press.linear().row(2).transpose();
  table_offset_mm_ = object_from_press.translation().z();
}

std::optional<double> ApproachView::table_height_mm(const Eigen::Vector2d& xy) const {
  // Below the table (z_object < 0) must lie below its height: the press frame's
  // z must rise with z_object.
  if (!(table_normal_.z() > kFacingCosine)) return std::nullopt;
  return -(table_normal_.x() * xy.x() + table_normal_.y() * xy.y() + table_offset_mm_) / table_normal_.z();
}

double ApproachView::height_mm(const Eigen::Vector2d& xy) const {
  double h = (object_ ? object_->height_mm(xy) : 0.0) - lift_mm_;  // the floor where no triangle is
  if (const auto table = table_height_mm(xy)) h = std::max(h, *table);
  return h;
}

double ApproachView::max_height_mm(const Eigen::Vector2d& centre, double radius) const {
  double top = (object_ ? object_->max_height_mm(centre, radius) : 0.0) - lift_mm_;
  // The plane's highest point over the disc.
  if (const auto table = table_height_mm(centre))
    top = std::max(top, *table + radius * table_normal_.head<2>().norm() / table_normal_.z());
  return top;
}

double ApproachView::overlap_mm(const Eigen::Vector2d& xy, double z) const {
  double overlap = object_ ? object_->overlap_mm(xy, z + lift_mm_) : -(z + lift_mm_);
  if (const auto table = table_height_mm(xy)) overlap = std::max(overlap, *table - z);
  return overlap;
}

Eigen::Isometry3d approach_frame(const Eigen::Vector3d& point_mm, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d z = -direction.normalized();
  // Any x across the press; the base's z makes a poor helper near the vertical.
  const Eigen::Vector3d helper = std::abs(z.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d x = helper.cross(z).normalized();
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = x;
  t.linear().col(1) = z.cross(x);
  t.linear().col(2) = z;
  t.translation() = point_mm;
  return t;
}

}  // namespace touchcloud::simulation
