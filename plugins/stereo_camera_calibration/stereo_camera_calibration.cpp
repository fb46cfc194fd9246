// stereo_camera_calibration: both cameras' intrinsics, lens distortion and
// the right camera's pose from images of a checkerboard held in air (Zhang's
// method, touchcloud/calibration/zhang_stereo.hpp). Reports the reprojection
// residual of every image pair; the refractive calibration takes the cameras
// on.
#include <cmath>
#include <sstream>

#include "touchcloud/calibration/zhang_stereo.hpp"
#include "touchcloud/plugin.hpp"

namespace touchcloud {

class StereoCameraCalibration final : public Stage {
  std::array<int, 2> board_corners_{};
  double square_mm_ = 10;
  calibration::StereoCalibrationOptions options_;

  sensor::Checkerboard board_;

  void declare_parameters(ParameterSet& p) override {
    p.add("board_corners", board_corners_, std::array<int, 2>{9, 6}).range(2, 100)
        .doc("inner corners of the board [cols, rows], as board_image_corners searched for");
    p.add("square_mm", square_mm_, 10.0).unit("mm").above(0).doc("edge of one printed square, measured");
    p.add("lens_model", options_.lens, calibration::LensModel::Radial2Tangential,
          {{"none", calibration::LensModel::None},
           {"k1_k2_p1_p2", calibration::LensModel::Radial2Tangential},
           {"k1_k2_p1_p2_k3", calibration::LensModel::Radial3Tangential}})
        .doc("the distortion coefficients estimated; the others stay 0");
    p.add("min_image_pairs", options_.min_views, 4).range(3, 100000).doc("fewer image pairs are refused");
    p.add("max_image_rms_px", options_.max_view_rms_px, 1.0).unit("px").above(0)
        .doc("an image whose reprojection RMS is larger is refused, by name");
  }

  void declare_ports(PortSet& ports) override {
    ports.input<BoardViewsPtr>("views", "the board's corners in every image pair (board_image_corners)");
    ports.output<StereoCamerasPtr>("cameras", "intrinsics, distortion and right_from_left (mm) of both cameras");
    ports.metric("image_rms_left_px", "px", "reprojection RMS of each image pair's left view").lower_is_better();
    ports.metric("image_rms_right_px", "px", "reprojection RMS of each image pair's right view").lower_is_better();
    ports.metric("rms_px", "px", "reprojection RMS of the stereo calibration").lower_is_better();
    for (const std::string camera : {"left", "right"}) {
      ports.metric(camera + "_fx_px", "px", camera + " camera's focal length along x");
      ports.metric(camera + "_fy_px", "px", camera + " camera's focal length along y");
      ports.metric(camera + "_cx_px", "px", camera + " camera's principal point, x");
      ports.metric(camera + "_cy_px", "px", camera + " camera's principal point, y");
    }
    ports.metric("baseline_mm", "mm", "distance between the cameras' centres");
    ports.metric("right_rotation_deg", "deg", "rotation of the right camera from the left");
  }

  void on_check(RunContext&) override { board_ = sensor::Checkerboard::from_parameters(board_corners_, square_mm_); }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& views = io.input<BoardViewsPtr>("views");
    if (!views) throw InputError("input 'views': no board views");
    const auto r = calibration::calibrate_stereo(*views, board_, options_);

    std::ostringstream residuals;
    for (const auto& v : r.views) {
      ctx.metric("image_rms_left_px", v.left_rms_px, "px");
      ctx.metric("image_rms_right_px", v.right_rms_px, "px");
      residuals << v.left_file << " " << v.left_rms_px << " px, " << v.right_file << " " << v.right_rms_px << " px\n";
    }
    ctx.note("image_residuals", residuals.str());
    const auto& c = r.cameras;
    ctx.metric("rms_px", r.rms_px, "px");
    ctx.metric("left_fx_px", c.left.fx_px, "px");
    ctx.metric("left_fy_px", c.left.fy_px, "px");
    ctx.metric("left_cx_px", c.left.cx_px, "px");
    ctx.metric("left_cy_px", c.left.cy_px, "px");
    ctx.metric("right_fx_px", c.right.fx_px, "px");
    ctx.metric("right_fy_px", c.right.fy_px, "px");
    ctx.metric("right_cx_px", c.right.cx_px, "px");
    ctx.metric("right_cy_px", c.right.cy_px, "px");
    ctx.metric("baseline_mm", c.right_from_left.translation().norm(), "mm");
    ctx.metric("right_rotation_deg", Eigen::AngleAxisd(c.right_from_left.linear()).angle() * 180 / M_PI, "deg");
    std::ostringstream s;
    s << r.views.size() << " image pairs: reprojection RMS " << r.rms_px << " px; left fx " << c.left.fx_px
      << " fy " << c.left.fy_px << " cx " << c.left.cx_px << " cy " << c.left.cy_px << " px; baseline "
      << c.right_from_left.translation().norm() << " mm";
    ctx.log(s.str());
    io.output("cameras", StereoCamerasPtr(std::make_shared<StereoCameras>(c)));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StereoCameraCalibration, "stereo_camera_calibration", calibration,
                  "Calibrates both cameras and their relative pose from board corners in air (Zhang, OpenCV)")
