// The flat acrylic plate between the cameras and the silicone gel: air,
// acrylic and silicone separated by two parallel planes. Expressed in one
// camera's frame (the left camera's in a StereoRig); lengths in mm.
#pragma once

#include <Eigen/Geometry>

namespace touchcloud::optics {

// The defaults for distance and thickness are plausible placeholders (the
// paper gives none); a real sensor's come from refractive calibration.
struct RefractivePlate {
  // Unit normal pointing from the camera into the gel.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  // Camera-side face: normal . X = distance_mm (d_xy, from the frame's origin).
  double distance_mm = 20.0;
  // Gel-side face: normal . X = distance_mm + thickness_mm. Zero collapses the
  // acrylic to a single air/silicone interface.
  double thickness_mm = 5.0;
  // Only the ratios matter; mu_air is conventionally 1.
  double mu_air = 1.0;
  double mu_acrylic = 1.49;
  double mu_silicone = 1.41;

  // Throws InputError naming each field that is wrong (`what` prefixes the names).
  void validate(const char* what = "plate") const;

  double gel_face_mm() const { return distance_mm + thickness_mm; }

  // The same plate in another frame: `other_from_this` maps this frame's points into it.
  RefractivePlate expressed_in(const Eigen::Isometry3d& other_from_this) const;
};

}  // namespace touchcloud::optics
