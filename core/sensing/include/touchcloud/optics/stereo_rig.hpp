// The GelStereo camera pair looking through the plate: two pinhole cameras,
// the right camera's pose relative to the left, and the plate in the left
// camera frame. Points are in the left camera frame, in mm.
#pragma once

#include <Eigen/Geometry>

#include "touchcloud/optics/pinhole_camera.hpp"
#include "touchcloud/optics/refractive_plate.hpp"
#include "touchcloud/optics/refractive_projection.hpp"

namespace touchcloud::optics {

enum class StereoSide { Left, Right };
const char* to_string(StereoSide side);

class StereoRig {
 public:
  // Validates everything, including that both camera centres are on the air
  // side of the plate; throws InputError naming what is wrong.
  StereoRig(PinholeCamera left, PinholeCamera right, const Eigen::Isometry3d& right_from_left,
            const RefractivePlate& plate_left);

  const PinholeCamera& camera(StereoSide side) const;
  const Eigen::Isometry3d& right_from_left() const { return right_from_left_; }
  const RefractivePlate& plate() const { return plate_; }  // in the left camera frame
  Eigen::Vector3d centre_mm(StereoSide side) const;        // optical centre, left frame
  Eigen::Isometry3d camera_from_left(StereoSide side) const;

  // The same rig with the cameras' roles exchanged (the right camera becomes
  // the reference frame).
  StereoRig swapped() const;

 private:
  PinholeCamera left_, right_;
  Eigen::Isometry3d right_from_left_;
  RefractivePlate plate_;
};

struct RefractedPixel {
  TraceStatus status = TraceStatus::Ok;  // Ok, OutOfView, PointNotInSilicone, NotConverged
  Eigen::Vector2d pixel_px = Eigen::Vector2d::Zero();  // also set when OutOfView off the image
};

// Forward projection: a point in the silicone (left frame) to its pixel in one camera.
RefractedPixel project_refracted(const StereoRig& rig, StereoSide side, const Eigen::Vector3d& point_left_mm);

// Back-projection: a pixel of one camera to its ray in the silicone (left
// frame). A pixel off the image is OutOfView.
SiliconeRay back_project_refracted(const StereoRig& rig, StereoSide side, const Eigen::Vector2d& pixel_px);

}  // namespace touchcloud::optics
