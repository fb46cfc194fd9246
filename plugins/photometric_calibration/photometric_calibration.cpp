// photometric_calibration: the photometric calibration of a GelSight-type
// sensor from presses of a ball of known radius (the usual GelSight
// procedure): each press is found in the image (the region that differs from
// the no-contact reference), the ball's shape gives every pixel inside it a
// known gradient, and a polynomial from colour difference to gradient is fitted
// to all presses at the end (sensor/photometric_calibration.hpp). Writes the
// calibration file, naming the sensor and its image size. `markers: mask`
// fills the gel's marker dots in both images first (imaging/marker_fill.hpp)
// and records it in the file (`markers: masked`).
#include <opencv2/core/version.hpp>

#include <optional>

#include "ball_press.hpp"
#include "touchcloud/library_versions.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/marker_mask_parameters.hpp"
#include "touchcloud/sensor/gelsight_sensor.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

namespace touchcloud {

namespace {
const LibraryVersion opencv_version("opencv", CV_VERSION);
}  // namespace

class PhotometricCalibrationStage final : public Stage {
  std::string sensor_file_, path_;
  double ball_radius_mm_ = 4.0;
  double detect_grey_ = 8.0;
  int degree_ = 3;
  imaging::MarkerMaskParameters markers_;
  std::optional<imaging::MarkerFill> marker_fill_;  // markers: mask
  sensor::GelSightSensor sensor_;  // read at check
  std::vector<Eigen::Vector3d> difference_;
  std::vector<Eigen::Vector2d> gradient_;
  long presses_ = 0, skipped_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("sensor", sensor_file_, std::string()).input_file()
        .doc("scene or sensor file whose sensor section has family: gelsight (name, image size, mm/px, gel)");
    p.add("ball_radius_mm", ball_radius_mm_, 4.0).unit("mm").above(0).doc("radius of the calibration ball");
    p.add("detect_grey", detect_grey_, 8.0).unit("grey levels").above(0).below(255)
        .doc("a pixel belongs to the press where its largest channel difference (3 x 3 mean) exceeds this");
    p.add("degree", degree_, 3).range(1, 5).doc("total degree of the polynomial from colour difference to gradient");
    p.add("path", path_, std::string("photometric_calibration.yaml")).output_file()
        .doc("calibration file in the output folder");
    markers_.declare(p);
  }

  void declare_ports(PortSet& ports) override {
    ports.input<MonoColourFramePtr>("image", "the sensor's image with the ball pressed in");
    ports.input<MonoColourFramePtr>("reference", "the same sensor's image without contact");
    ports.metric("press_contact_radius_mm", "mm", "contact radius of the ball in this frame");
    ports.metric("presses", "presses", "frames with a ball press found").final();
    ports.metric("frames_skipped", "frames", "frames without a ball press").final();
    ports.metric("samples", "px", "pixels the colour-to-gradient fit used").final();
    ports.metric("rms_gradient", "1", "root mean square gradient residual of the fit").final().lower_is_better();
    ports.artifact(ArtifactRole::calibration, "the photometric calibration file");
  }

  void on_check(RunContext&) override {
    try {
      sensor_ = sensor::load_gelsight_sensor(sensor_file_);
    } catch (const InputError& e) {
      throw ParameterError("sensor", e.what());
    }
  }

  void on_configure(RunContext&) override { marker_fill_ = markers_.make_fill(); }

  void require_frame(const MonoColourFramePtr& f, const std::string& port) const {
    const std::string where = "input '" + port + "'";
    if (!f || f->image.empty()) throw InputError(where + ": no image");
    if (f->image.type() != CV_8UC3)
      throw InputError(where + ": the image is " + cv::typeToString(f->image.type()) + "; expected 8-bit BGR");
    if (f->image.cols != sensor_.width_px || f->image.rows != sensor_.height_px)
      throw InputError(where + ": the image is " + std::to_string(f->image.cols) + " x " +
                       std::to_string(f->image.rows) + " px, but sensor " + sensor_.name + " (" + sensor_file_ +
                       ") has " + std::to_string(sensor_.width_px) + " x " + std::to_string(sensor_.height_px));
    if (!f->sensor.empty() && f->sensor != sensor_.name)
      throw InputError(where + ": the image is of sensor '" + f->sensor + "', not of '" + sensor_.name + "' (" +
                       sensor_file_ + ")");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& image = io.input<MonoColourFramePtr>("image");
    const auto& reference = io.input<MonoColourFramePtr>("reference");
    require_frame(image, "image");
    require_frame(reference, "reference");
    cv::Mat seen = image->image, gel = reference->image;
    if (marker_fill_) {
      const imaging::FilledPair filled = marker_fill_->fill(seen, gel);
      seen = filled.image.clone();
      gel = filled.reference.clone();
    }
    std::string why;
    const auto press =
        photometric::find_ball_press(seen, gel, detect_grey_, ball_radius_mm_, sensor_.mm_per_px, why);
    if (!press) {
      ++skipped_;
      ctx.log("frame " + std::to_string(image->index) + " skipped: " + why);
      return;
    }
    ++presses_;
    const std::size_t before = difference_.size();
    photometric::ball_samples(seen, gel, *press, ball_radius_mm_, sensor_.mm_per_px, difference_, gradient_);
    ctx.metric("press_contact_radius_mm", press->contact_radius_px * sensor_.mm_per_px, "mm");
    ctx.log("press at (" + std::to_string(press->centre_px.x()) + ", " + std::to_string(press->centre_px.y()) +
            ") px, contact radius " + std::to_string(press->contact_radius_px * sensor_.mm_per_px) + " mm: " +
            std::to_string(difference_.size() - before) + " samples");
  }

  void on_finish(RunContext& ctx) override {
    if (presses_ == 0)
      throw InputError("photometric calibration: none of the " + std::to_string(skipped_) +
                       " frames shows a ball press (see the log for why)");
    sensor::PhotometricCalibration c = sensor::fit_photometric_calibration(difference_, gradient_, degree_);
    c.sensor = sensor_.name;
    c.width_px = sensor_.width_px;
    c.height_px = sensor_.height_px;
    c.mm_per_px = sensor_.mm_per_px;
    c.gel_thickness_mm = sensor_.gel_thickness_mm;
    c.markers_masked = marker_fill_.has_value();
    sensor::write_photometric_calibration(c, ctx.output_path(path_));
    ctx.artifact(ArtifactRole::calibration, path_, {{"kind", std::string("photometric")}});
    ctx.metric("presses", static_cast<double>(presses_), "presses");
    ctx.metric("frames_skipped", static_cast<double>(skipped_), "frames");
    ctx.metric("samples", static_cast<double>(c.samples), "px");
    ctx.metric("rms_gradient", c.rms_gradient, "1");
    ctx.log("wrote " + path_ + ": " + std::to_string(c.samples) + " samples from " + std::to_string(presses_) +
            " presses, gradient residual rms " + std::to_string(c.rms_gradient));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::PhotometricCalibrationStage, "photometric_calibration", calibration,
                  "Photometric calibration of a GelSight-type sensor from ball presses: colour difference to gradient")
