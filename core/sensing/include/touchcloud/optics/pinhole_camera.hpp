// A pinhole camera with Brown-Conrady lens distortion, in OpenCV's conventions:
// camera frame x right, y down, z forward; pixel (0, 0) is the centre of the
// top-left pixel; distortion coefficients in OpenCV's order (k1, k2, p1, p2, k3).
#pragma once

#include <Eigen/Core>

#include "touchcloud/optics/trace_status.hpp"

namespace touchcloud::optics {

struct BrownConrady {
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
};

// Defaults: the GelStereo 2.0 simulator's camera (gelstereo_palm2.md).
struct CameraIntrinsics {
  int width_px = 1280;
  int height_px = 720;
  double fx_px = 651.5;
  double fy_px = 652.0;
  double cx_px = 598.6;
  double cy_px = 377.1;
  BrownConrady distortion;

  // Throws InputError naming each field that is wrong (`what` prefixes the names).
  void validate(const char* what = "camera") const;
};

struct PixelProjection {
  TraceStatus status = TraceStatus::Ok;  // Ok, OutOfView, BehindCamera
  // Also set when OutOfView because off the image; zero past the fold radius
  // or behind the camera.
  Eigen::Vector2d pixel_px = Eigen::Vector2d::Zero();
};

struct PixelDirection {
  TraceStatus status = TraceStatus::Ok;  // Ok or UndistortionFailed
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // unit, camera frame, z > 0
};

class PinholeCamera {
 public:
  explicit PinholeCamera(const CameraIntrinsics& intrinsics = {});  // validates

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }

  // A point (or direction) in the camera frame to its pixel. Points past the
  // radius where the distortion polynomial folds back are OutOfView: the
  // model would put them at a wrong, in-image pixel.
  PixelProjection project(const Eigen::Vector3d& point_camera) const;

  // A pixel (anywhere, on or off the image) to the unit direction of its ray.
  PixelDirection back_project(const Eigen::Vector2d& pixel_px) const;

  // Whether the pixel lies on the image: [-0.5, width - 0.5) x [-0.5, height - 0.5).
  bool in_view(const Eigen::Vector2d& pixel_px) const;

  // The lens model on normalised image coordinates (x/z, y/z).
  Eigen::Vector2d distort(const Eigen::Vector2d& undistorted) const;
  // Inverse of distort by Newton's method; status UndistortionFailed when it
  // does not converge or lands past the fold radius.
  TraceStatus undistort(const Eigen::Vector2d& distorted, Eigen::Vector2d& undistorted) const;

  // Squared normalised radius where d(r L(r^2))/dr first reaches 0 (infinity if never).
  double fold_radius2() const { return fold_radius2_; }

 private:
  CameraIntrinsics intrinsics_;
  double fold_radius2_;
};

}  // namespace touchcloud::optics
