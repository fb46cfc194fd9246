// Stereo camera calibration by Zhang's method: each camera's intrinsics and
// lens distortion from views of a flat checkerboard (cv::calibrateCamera),
// then both cameras and the right camera's pose refined together
// (cv::stereoCalibrate). Board in mm, so the baseline comes out in mm.
#pragma once

#include <string>
#include <vector>

#include "touchcloud/sensor/checkerboard.hpp"
#include "touchcloud/types/board_views.hpp"
#include "touchcloud/types/stereo_cameras.hpp"

namespace touchcloud::calibration {

// Which Brown-Conrady coefficients are estimated; the others stay 0.
enum class LensModel { None, Radial2Tangential, Radial3Tangential };

struct StereoCalibrationOptions {
  LensModel lens = LensModel::Radial2Tangential;
  int min_views = 4;
  // A view whose reprojection RMS (either camera) is larger means wrong
  // corners or a lens model that does not fit: refused, naming the image.
  double max_view_rms_px = 1.0;
};

struct ViewResidual {
  std::string left_file, right_file;
  double left_rms_px = 0, right_rms_px = 0;  // reprojection RMS after the joint fit
};

struct StereoCalibrationResult {
  StereoCameras cameras;
  double rms_px = 0;                             // over every corner of both cameras, joint fit
  double left_alone_rms_px = 0, right_alone_rms_px = 0;  // each camera's own fit, before the joint one
  std::vector<ViewResidual> views;               // in the order of the input
};

// InputError naming what is wrong: a board of another size than the views',
// too few views, a view that does not fit (naming its images). RunError when
// OpenCV fails or returns non-finite numbers.
StereoCalibrationResult calibrate_stereo(const BoardViews& views, const sensor::Checkerboard& board,
                                         const StereoCalibrationOptions& options);

}  // namespace touchcloud::calibration
