// checkerboard_press: simulated checkerboard presses for refractive
// calibration. One call is one press: the board pressed into the gel of the
// TRUE sensor, its inner corners imaged through the plate by both cameras,
// with pixel noise; what cv::findChessboardCorners would give on real images.
#include <cmath>
#include <sstream>

#include "touchcloud/number_text.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/sensor_parameters.hpp"
#include "touchcloud/simulation/board/board_press.hpp"

namespace touchcloud {

class CheckerboardPress final : public Stage {
  sensor::SensorParameters sensor_;
  std::array<int, 2> board_corners_{};
  std::vector<double> presses_;
  std::array<double, 2> depth_range_mm_{};
  double square_mm_ = 4, max_tilt_deg_ = 25, noise_px_ = 0.1, min_height_mm_ = 0.5;
  int random_presses_ = 12;

  sensor::GelStereoSensor sensor_read_;  // the true sensor, read at check

  std::unique_ptr<optics::StereoRig> rig_;
  Eigen::Isometry3d left_from_sensor_ = Eigen::Isometry3d::Identity();
  double gel_radius_mm_ = 0;
  sensor::Checkerboard board_;
  std::vector<simulation::BoardPose> poses_;
  std::size_t next_ = 0;

  void declare_parameters(ParameterSet& p) override {
    sensor_.declare(p, "the TRUE sensor: a scene or sensor file with a 'sensor:' section");
    p.add("board_corners", board_corners_, std::array<int, 2>{8, 6}).range(2, 100)
        .doc("inner corners of the board [cols, rows]");
    p.add("square_mm", square_mm_, 4.0).unit("mm").above(0).doc("edge of one board square");
    p.add("presses", presses_, std::vector<double>{}).doc(
        "explicit presses, [tilt_x_deg, tilt_y_deg, depth_mm] per press, flattened; empty: random_presses");
    p.add("random_presses", random_presses_, 12).range(1, 1000)
        .doc("number of seeded random presses when 'presses' is empty");
    p.add("max_tilt_deg", max_tilt_deg_, 25.0).unit("deg").range(0, 60)
        .doc("largest board tilt of the random presses (uniform in [0, max])");
    p.add("depth_range_mm", depth_range_mm_, std::array<double, 2>{4, 10}).unit("mm").above(0)
        .doc("[min, max] press depth of the random presses, into the gel hemisphere");
    p.add("noise_px", noise_px_, 0.1).unit("px").at_least(0).doc("Gaussian corner noise, sigma per coordinate");
    p.add("min_height_mm", min_height_mm_, 0.5).unit("mm").at_least(0)
        .doc("corners closer than this to the gel face are dropped (not pressed into the gel)");
    p.rule({"depth_range_mm"}, [this]() -> std::optional<std::string> {
      if (depth_range_mm_[0] <= depth_range_mm_[1]) return std::nullopt;
      return "must be [min, max] with min <= max";
    });
    p.rule({"presses"}, [this]() -> std::optional<std::string> {
      if (presses_.size() % 3 == 0) return std::nullopt;
      return "has " + std::to_string(presses_.size()) + " numbers; give [tilt_x_deg, tilt_y_deg, depth_mm] per press";
    });
  }

  void declare_ports(PortSet& ports) override {
    ports.output<MarkerSetPtr>("corners", "corner pixels of one press in both views; id = corner index (row-major)");
    ports.output<bool>("last_press", "true on the last press (use as the loop's until)");
    ports.metric("corners_seen", "", "board corners of this press seen in both views");
  }

  void on_check(RunContext&) override {
    board_ = sensor::Checkerboard::from_parameters(board_corners_, square_mm_);
    sensor_read_ = sensor_.load(true);
    const auto& sensor = sensor_read_;
    for (std::size_t i = 0; i + 2 < presses_.size(); i += 3) {
      const double depth = presses_[i + 2];
      if (std::abs(presses_[i]) >= 90 || std::abs(presses_[i + 1]) >= 90 || !(depth > 0) ||
          depth > sensor.gel.radius_mm())
        throw ParameterError("presses", "press " + std::to_string(i / 3) + ": tilts must be within (-90, 90) deg"
                                        " and the depth in (0, " + number_text(sensor.gel.radius_mm()) + "] mm");
    }
    if (depth_range_mm_[1] > sensor.gel.radius_mm())
      throw ParameterError("depth_range_mm", "goes deeper than the gel's radius");
  }

  void on_configure(RunContext& ctx) override {
    const auto& sensor = sensor_read_;
    rig_ = std::make_unique<optics::StereoRig>(sensor_.rig(sensor, true));
    left_from_sensor_ = sensor.sensor_from_left_camera().inverse();
    gel_radius_mm_ = sensor.gel.radius_mm();
    poses_.clear();
    for (std::size_t i = 0; i + 2 < presses_.size(); i += 3) {
      simulation::BoardPose pose;
      pose.tilt_deg = {presses_[i], presses_[i + 1]};
      pose.depth_mm = presses_[i + 2];
      poses_.push_back(pose);
    }
    if (poses_.empty())
      poses_ = simulation::random_board_poses(random_presses_, max_tilt_deg_,
                                               {depth_range_mm_[0], depth_range_mm_[1]}, ctx.rng());
    next_ = 0;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    if (next_ >= poses_.size())
      throw ParameterError(presses_.empty() ? "random_presses" : "presses",
                           "all " + std::to_string(poses_.size()) + " presses are used; end the loop with "
                           "'until: <this stage>.last_press' or fewer max_iterations");
    const auto& pose = poses_[next_];
    const auto corners = simulation::board_corners_sensor(board_, pose, gel_radius_mm_);
    const auto set = simulation::image_press(*rig_, left_from_sensor_, corners, gel_radius_mm_,
                                              {noise_px_, min_height_mm_}, ctx.rng());
    std::ostringstream s;
    s << "press " << next_ << ": tilt [" << pose.tilt_deg.x() << ", " << pose.tilt_deg.y() << "] deg, depth "
      << pose.depth_mm << " mm, " << set->matches.size() << " of " << corners.size() << " corners seen";
    ctx.log(s.str());
    ctx.metric("corners_seen", static_cast<double>(set->matches.size()));
    ++next_;
    io.output("corners", MarkerSetPtr(set));
    io.output("last_press", next_ == poses_.size());
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::CheckerboardPress, "checkerboard_press", simulation,
                  "Simulates checkerboard presses into the gel: corner pixels in both views, for calibration")
