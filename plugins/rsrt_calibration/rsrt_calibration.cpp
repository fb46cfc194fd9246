// rsrt_calibration: refractive calibration of the GelStereo plate from
// checkerboard presses. Takes the presses one per loop iteration (input
// 'corners', the simulator's way) or all at once (input 'views', corners
// found in images), and optionally the cameras from stereo calibration in
// place of the initial guess's; on finish it estimates d_xy, the plate normal
// and mu_silicone (touchcloud/calibration/plate_calibration.hpp) and writes
// the calibrated sensor file.
#include <cmath>
#include <sstream>

#include "touchcloud/calibration/plate_calibration.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/sensor_parameters.hpp"
#include "touchcloud/types/board_views.hpp"
#include "touchcloud/types/stereo_cameras.hpp"

namespace touchcloud {

class RsrtCalibration final : public Stage {
  sensor::SensorParameters sensor_;
  std::string output_;
  calibration::BoardSpans distances_ = calibration::BoardSpans::AllPairs;
  std::array<int, 2> board_corners_{};
  double square_mm_ = 4, min_board_tilt_deg_ = 5;
  bool diagonals_ = true;
  int min_corners_per_press_ = 9;

  calibration::Checkerboard board_;
  sensor::GelStereoSensor sensor_read_;  // the initial guess, read at check
  std::vector<calibration::PressCorners> presses_;
  std::vector<std::string> press_names_;  // for the per-press residuals
  StereoCamerasPtr cameras_;              // from stereo calibration, when connected

  void declare_parameters(ParameterSet& p) override {
    sensor_.declare(p, "the initial guess: a scene or sensor file with a 'sensor:' section (cameras known, plate "
                       "guessed)");
    p.add("board_corners", board_corners_, std::array<int, 2>{8, 6}).range(2, 100)
        .doc("inner corners of the board [cols, rows]; corner id = row * cols + col");
    p.add("square_mm", square_mm_, 4.0).unit("mm").above(0).doc("edge of one board square");
    p.add("output", output_, std::string("calibrated_sensor.yaml")).output_file()
        .doc("the calibrated sensor file, in the output folder");
    p.add("distances", distances_, calibration::BoardSpans::AllPairs,
          {{"all_pairs", calibration::BoardSpans::AllPairs},
           {"rows_and_columns", calibration::BoardSpans::RowsAndColumns},
           {"neighbours", calibration::BoardSpans::Neighbours}})
        .doc("corner pairs whose distances are fitted; neighbours (the paper's) is biased by pixel noise");
    p.add("diagonals", diagonals_, true).doc("with rows_and_columns or neighbours: also fit the squares' diagonals");
    p.add("min_corners_per_press", min_corners_per_press_, 9).range(4, 10000)
        .doc("a press with fewer corners seen by both cameras is refused");
    p.add("min_board_tilt_deg", min_board_tilt_deg_, 5.0).unit("deg").range(0, 89)
        .doc("some press must tilt the board this far from the plate, or mu_silicone is not determined");
  }

  void declare_ports(PortSet& ports) override {
    ports.optional_input<MarkerSetPtr>("corners", "one press: corner pixels in both views, id = corner index, "
                                                  "matched (connect this or 'views')");
    ports.optional_input<BoardViewsPtr>("views", "every press at once: corners found in images (board_image_corners)");
    ports.optional_input<StereoCamerasPtr>("cameras", "the cameras from stereo calibration; replace the initial "
                                                      "guess's intrinsics, distortion and right_from_left");
    ports.metric("press_corners", "", "corners of each press");
    ports.metric("press_corner_error_mm", "mm", "each press's mean corner-distance error through the calibrated rig")
        .lower_is_better();
    ports.metric("mean_corner_error_before_mm", "mm", "mean corner-distance error with the initial guess").final();
    ports.metric("mean_corner_error_after_mm", "mm", "mean corner-distance error after calibration")
        .final()
        .lower_is_better();
    ports.metric("d_xy_mm", "mm", "calibrated distance of the plate from the left camera").final();
    ports.metric("plate_tilt_x_deg", "deg", "calibrated plate tilt about x").final();
    ports.metric("plate_tilt_y_deg", "deg", "calibrated plate tilt about y").final();
    ports.metric("normal_change_deg", "deg", "angle between the initial and calibrated plate normals").final();
    ports.metric("mu_silicone", "", "calibrated refractive index of the gel").final();
    ports.metric("sigma_d_xy_mm", "mm", "standard deviation of d_xy_mm").final().lower_is_better();
    ports.metric("sigma_normal_deg", "deg", "standard deviation of the plate normal").final().lower_is_better();
    ports.metric("sigma_mu_silicone", "", "standard deviation of mu_silicone").final().lower_is_better();
    ports.metric("condition_number", "", "condition number of the fit's Jacobian").final().lower_is_better();
    ports.metric("max_board_tilt_deg", "deg", "largest board tilt among the presses").final();
    ports.metric("iterations", "", "iterations of the least-squares solver").final();
    ports.artifact(ArtifactRole::calibration, "the sensor file with the calibrated plate");
  }

  void on_check(RunContext&) override {
    board_ = sensor::Checkerboard::from_parameters(board_corners_, square_mm_);
    const std::string ext = std::filesystem::path(output_).extension().string();
    if (ext != ".yaml" && ext != ".yml")
      throw ParameterError("output", "'" + output_ + "': a sensor file is YAML (.yaml or .yml)");
    sensor_read_ = sensor_.load(true);
  }

  void on_configure(RunContext&) override {
    presses_.clear();
    press_names_.clear();
    cameras_.reset();
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    if (io.has("corners") == io.has("views"))
      throw InputError("connect exactly one of the inputs 'corners' (one press per call) and 'views' (all presses)");
    if (const auto* cameras = io.optional_input<StereoCamerasPtr>("cameras")) {
      if (!*cameras) throw InputError("input 'cameras': no cameras");
      if (!sensor_.lens_distortion)
        throw ParameterError("lens_distortion", "must be true with calibrated cameras on input 'cameras': their "
                                                "lens distortion is part of the calibration");
      cameras_ = *cameras;
    }
    if (io.has("views")) {
      const auto& views = io.input<BoardViewsPtr>("views");
      if (!views) throw InputError("input 'views': no board views");
      if (views->cols != board_.cols || views->rows != board_.rows)
        throw ParameterError("board_corners", "the corners on input 'views' were found on a " +
                                                  std::to_string(views->cols) + " x " + std::to_string(views->rows) +
                                                  " board");
      for (const auto& view : views->views) {
        if (!view.corners) throw InputError("images " + view.left_file + ", " + view.right_file + ": no corners");
        add_press(calibration::press_corners_from(*view.corners, board_, "images " + view.left_file + ", " +
                                                                                  view.right_file),
                  std::filesystem::path(view.left_file).filename().string(), ctx);
      }
      return;
    }
    const auto& markers = io.input<MarkerSetPtr>("corners");
    const std::string what = "press " + std::to_string(presses_.size()) + " (input 'corners')";
    if (!markers) throw InputError(what + ": no marker set");
    add_press(calibration::press_corners_from(*markers, board_, what), "press " + std::to_string(presses_.size()),
              ctx);
  }

  void add_press(calibration::PressCorners press, std::string name, RunContext& ctx) {
    presses_.push_back(std::move(press));
    press_names_.push_back(std::move(name));
    ctx.metric("press_corners", static_cast<double>(presses_.back().corners.size()));
  }

  void on_finish(RunContext& ctx) override {
    if (presses_.empty()) throw InputError("no presses arrived on input 'corners': nothing to calibrate");
    sensor::GelStereoSensor sensor = sensor_read_;
    if (cameras_) {
      sensor.cameras.left = cameras_->left;
      sensor.cameras.right = cameras_->right;
      sensor.cameras.right_from_left = cameras_->right_from_left;
    }
    const optics::StereoRig initial = [&] {
      try {
        return sensor_.rig(sensor, true);
      } catch (const InputError& e) {
        throw InputError(std::string("the calibrated cameras (input 'cameras') do not fit the initial guess's plate: ") +
                         e.what());
      }
    }();
    calibration::PlateCalibrationOptions options;
    options.spans = distances_;
    options.use_diagonals = diagonals_;
    options.min_corners_per_press = min_corners_per_press_;
    options.min_board_tilt_deg = min_board_tilt_deg_;
    const auto result = calibration::calibrate_plate(initial, board_, presses_, options);

    sensor::set_plate_from_left_frame(sensor, result.plate);
    std::ostringstream comment;
    comment << "Refractive calibration (touchcloud rsrt_calibration) from " << result.presses << " presses, "
            << result.corners << " corners of a " << board_.cols << " x " << board_.rows << " board, "
            << board_.square_mm << " mm squares.\n"
            << "Initial guess: " << sensor_.file << "\n"
            << "Estimated: d_xy = " << result.plate.distance_mm << " mm, mu_silicone = " << result.plate.mu_silicone
            << "; fixed: mu_air, mu_acrylic, thickness_mm.\n"
            << "Mean corner-distance error " << result.mean_corner_error_before_mm << " mm before, "
            << result.mean_corner_error_after_mm << " mm after; " << result.iterations << " iterations; "
            << result.termination;
    // Each press's own residual, for finding a bad image: the mean
    // corner-distance error (mm) through the calibrated rig.
    const optics::StereoRig calibrated = sensor_.rig(sensor, true);
    std::ostringstream per_press;
    for (std::size_t i = 0; i < presses_.size(); ++i) {
      const double error = calibration::mean_corner_error_mm(calibrated, board_, {presses_[i]});
      ctx.metric("press_corner_error_mm", error, "mm");
      per_press << press_names_[i] << " " << error << " mm\n";
    }
    ctx.note("press_residuals", per_press.str());
    if (cameras_) comment << "\nCameras from stereo calibration (input 'cameras').";

    std::filesystem::path file;
    try {
      file = ctx.output_path(output_);
    } catch (const ParameterError& e) {
      throw ParameterError("output", e.detail());
    }
    sensor::write_gelstereo_sensor(sensor, file, comment.str());
    ctx.artifact(ArtifactRole::calibration, output_, {{"kind", std::string("gelstereo_sensor")}});

    ctx.metric("mean_corner_error_before_mm", result.mean_corner_error_before_mm, "mm");
    ctx.metric("mean_corner_error_after_mm", result.mean_corner_error_after_mm, "mm");
    ctx.metric("d_xy_mm", result.plate.distance_mm, "mm");
    ctx.metric("plate_tilt_x_deg", sensor.plate.tilt_deg.x(), "deg");
    ctx.metric("plate_tilt_y_deg", sensor.plate.tilt_deg.y(), "deg");
    ctx.metric("normal_change_deg", result.normal_change_deg, "deg");
    ctx.metric("mu_silicone", result.plate.mu_silicone);
    ctx.metric("sigma_d_xy_mm", result.sigma_d_xy_mm, "mm");
    ctx.metric("sigma_normal_deg", result.sigma_normal_deg, "deg");
    ctx.metric("sigma_mu_silicone", result.sigma_mu_silicone);
    ctx.metric("condition_number", result.condition_number);
    ctx.metric("max_board_tilt_deg", result.max_board_tilt_deg, "deg");
    ctx.metric("iterations", result.iterations);
    ctx.note("termination", result.termination);
    std::ostringstream s;
    s << "d_xy " << result.plate.distance_mm << " mm, tilt [" << sensor.plate.tilt_deg.x() << ", "
      << sensor.plate.tilt_deg.y() << "] deg, mu_silicone " << result.plate.mu_silicone << "; mean corner error "
      << result.mean_corner_error_before_mm << " -> " << result.mean_corner_error_after_mm << " mm ("
      << result.iterations << " iterations, " << result.termination << "); wrote " << output_;
    ctx.log(s.str());
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::RsrtCalibration, "rsrt_calibration", calibration,
                  "Calibrates the plate (d_xy, normal, mu_silicone) from checkerboard presses; writes a sensor file")
