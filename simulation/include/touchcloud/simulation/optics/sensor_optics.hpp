// The scene's cameras and plate as the optics library models them, and the
// projection of markers (sensor frame) into the two views. All projection
// goes through touchcloud/optics: with refraction, the Snell-invariant
// forward projection through the plate; without it, straight rays (the
// pinhole model).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/simulation/scene/scene.hpp"
#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::simulation {

using optics::StereoSide;

struct MarkerPixel {
  int id = -1;                                  // marker id (index in the layout)
  Eigen::Vector2d pixel_px = Eigen::Vector2d::Zero();
  double radius_px = 0;                         // apparent radius of the printed dot
};

// Markers one camera sees, in marker id order.
using ViewPixels = std::vector<MarkerPixel>;

class SensorOptics {
 public:
  // Throws InputError naming `sensor.plate` when, with refraction, no ray of
  // a camera gets through the plate (every one totally reflected or missing it).
  SensorOptics(const Scene& scene, bool refraction, bool lens_distortion);

  // The rig as a triangulation stage should be given it: the scene's plate
  // with refraction, a plate of equal indices (straight rays) without.
  const optics::StereoRig& rig() const { return rig_; }
  const Eigen::Isometry3d& left_from_sensor() const { return left_from_sensor_; }
  bool refraction() const { return refraction_; }

  // The pixel of a marker, or nothing when the camera does not see it: off
  // the image, or its light path would cross the plate outside the gel's base.
  bool project(StereoSide side, const Eigen::Vector3d& marker_sensor_mm, Eigen::Vector2d& pixel_px) const;

  // Every marker one camera sees; `dot_diameter_mm` sets radius_px (0: skip).
  ViewPixels view(StereoSide side, const std::vector<Eigen::Vector3d>& markers_sensor_mm,
                  double dot_diameter_mm) const;

 private:
  double apparent_depth_mm(StereoSide side, const Eigen::Vector3d& marker_left_mm) const;

  optics::StereoRig rig_;
  Eigen::Isometry3d left_from_sensor_;
  double gel_radius_mm_;
  bool refraction_;
};

}  // namespace touchcloud::simulation
