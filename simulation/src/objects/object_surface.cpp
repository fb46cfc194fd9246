#include "touchcloud/simulation/objects/object_surface.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/simulation/objects/analytic_surfaces.hpp"
#include "touchcloud/simulation/objects/mesh_surface.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::simulation {

namespace {

// An analytic height field, scaled, turned about z and moved on the table.
class PlacedAnalyticSurface final : public ObjectSurface {
 public:
  PlacedAnalyticSurface(const AnalyticSurface& surface, double scale, const Eigen::Isometry3d& base_from_object)
      : surface_(surface), scale_(scale), object_from_base_(base_from_object.inverse()),
        lift_mm_(base_from_object.translation().z()) {}

  double height_mm(const Eigen::Vector2d& xy) const override {
    const Eigen::Vector3d local = object_from_base_ * Eigen::Vector3d(xy.x(), xy.y(), 0.0) / scale_;
    if (!surface_.footprint_mm.contains(local.head<2>())) return 0.0;
    return std::max(0.0, scale_ * surface_.height_mm(local.x(), local.y()) + lift_mm_);
  }

  // Sampled on a 0.25 mm grid: the true maximum exceeds the sampled one by at
  // most the slope at the peak times 0.18 mm (0.5 mm at the fox's ear tips,
  // scaled with the object), which the safe clearance covers.
  double max_height_mm(const Eigen::Vector2d& centre, double radius) const override {
    constexpr double kStep = 0.25;
    const int n = static_cast<int>(std::ceil(radius / kStep));
    double top = 0.0;
    for (int iy = -n; iy <= n; ++iy)
      for (int ix = -n; ix <= n; ++ix) {
        const Eigen::Vector2d d(ix * kStep, iy * kStep);
        if (d.squaredNorm() <= radius * radius) top = std::max(top, height_mm(centre + d));
      }
    return top;
  }

 private:
  const AnalyticSurface& surface_;
  double scale_;
  Eigen::Isometry3d object_from_base_;
  double lift_mm_;
};

class FlatTop final : public ObjectSurface {
 public:
  explicit FlatTop(double height_mm) : height_mm_(height_mm) {}
  double height_mm(const Eigen::Vector2d&) const override { return height_mm_; }
  double max_height_mm(const Eigen::Vector2d&, double) const override { return height_mm_; }

 private:
  double height_mm_;
};

std::unique_ptr<ObjectSurface> mesh_object(const ObjectSpec& object) {
  const scoring::TriangleMesh mesh = read_placed_object_mesh(object);
  try {
    return std::make_unique<MeshSurface>(mesh);
  } catch (const InputError& e) {
    throw InputError("scene object.mesh (" + object.mesh.string() + "): " + e.what(), object.where);
  }
}

}  // namespace

std::unique_ptr<ObjectSurface> make_object_surface(const ObjectSpec& object) {
  switch (object.kind) {
    case ObjectKind::Mesh: return mesh_object(object);
    case ObjectKind::FoxMask:
      return std::make_unique<PlacedAnalyticSurface>(fox_mask(), object.scale, object.base_from_object);
    case ObjectKind::WaveSurface:
      return std::make_unique<PlacedAnalyticSurface>(wave_surface(), object.scale, object.base_from_object);
    case ObjectKind::Plane:
      return std::make_unique<FlatTop>(std::max(0.0, object.scale * object.plane_height_mm +
                                                        object.base_from_object.translation().z()));
  }
  throw InputError("scene object: unknown kind");
}

}  // namespace touchcloud::simulation
