// The robot's touch, one camera frame at a time. The sensor faces down
// (base_from_sensor = translation(x, y, h) * rotation of 180 deg about x,
// PressTarget::sensor_pose); a touch starts with the gel's apex `safe_clearance_mm` above the highest
// object point under the gel, descends along -z_B by approach_speed / fps per
// frame until a frame in which the gel touches the object, then by speed /
// fps, and, on the frame after the pipeline reports a stable contact, presses
// `press_depth_mm` further: that frame is the recorded one, and the touch ends.
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Geometry>

#include "touchcloud/simulation/scene/scene.hpp"

namespace touchcloud::simulation {

// What a touch presses at: a point (x, y) of the approach frame, approached
// along its -z with the gel facing that way. The approach frame is the base
// frame (straight down, the gel facing the table) unless base_from_approach
// places it: a touch from any side. Everything that moves the sensor along a
// touch asks the target for the pose, so the approach is defined here alone.
struct PressTarget {
  Eigen::Vector2d xy_mm = Eigen::Vector2d::Zero();
  std::optional<Eigen::Isometry3d> base_from_approach;  // not set: the base frame

  PressTarget() = default;
  // A point of the base frame (mm) is a target: it is pressed straight down.
  PressTarget(const Eigen::Vector2d& point_xy_mm) : xy_mm(point_xy_mm) {}  // NOLINT(google-explicit-constructor)
  PressTarget(double x_mm, double y_mm) : xy_mm(x_mm, y_mm) {}
  PressTarget(const Eigen::Vector2d& point_xy_mm, const std::optional<Eigen::Isometry3d>& approach)
      : xy_mm(point_xy_mm), base_from_approach(approach) {}

  // The sensor's pose in the approach frame with its origin `height_mm`
  // above the approach frame's z = 0 (the table, from above).
  Eigen::Isometry3d sensor_pose(double height_mm) const;
  bool operator==(const PressTarget& other) const;
};

struct TouchStep {
  int touch = 0;                 // touch number in the run, from 0
  int frame_in_touch = 0;        // 0 at the safe height
  bool pressed = false;          // the recorded frame
  PressTarget target;
  // The sensor's true pose in the frame the press runs in: the approach
  // frame (the base frame from above), or the object's frame on a turntable.
  Eigen::Isometry3d press_from_sensor = Eigen::Isometry3d::Identity();
  // The true pose in the robot's base frame (the same as press_from_sensor
  // for a touch from above without a turntable).
  Eigen::Isometry3d base_from_sensor = Eigen::Isometry3d::Identity();
};

class TouchMotion {
 public:
  // `seed` keys the press depth drawn per touch when the robot has a press_depth_range_mm.
  TouchMotion(const RobotSpec& robot, double fps, std::uint64_t seed = 0)
      : robot_(robot),
        seed_(seed),
        step_mm_(robot.speed_mm_s / fps),
        approach_step_mm_((robot.approach_speed_mm_s > 0 ? robot.approach_speed_mm_s : robot.speed_mm_s) / fps) {}

  bool touching() const { return touching_; }
  int touches_started() const { return touch_ + 1; }
  // The next frame. A touch starts (at `start_height_mm`, the sensor origin's
  // height) when none is under way; during one, the target must stay the same
  // (RunError otherwise) and `previous_stable` says whether the pipeline found
  // the previous frame's contact stable.
  TouchStep next(const PressTarget& target, double start_height_mm, bool previous_stable);

  // Tells the motion whether the gel overlaps the object in the frame just
  // stepped; RunError when it is more than max_contact_depth_mm past first
  // contact without a stable contact, saying whether earlier touches settled
  // (then the contact failed, not the wiring).
  void observe_overlap(bool overlapping);
  double travel_past_contact_mm() const { return first_contact_ ? *first_contact_ - height_ : 0.0; }
  const RobotSpec& robot() const { return robot_; }
  // The further press of the touch under way (or the last one), mm.
  double press_depth_mm() const { return press_depth_mm_; }

 private:
  RobotSpec robot_;
  std::uint64_t seed_;
  double press_depth_mm_ = robot_.press_depth_mm;
  double step_mm_, approach_step_mm_;
  bool touching_ = false;
  int touch_ = -1, frame_ = 0;
  int settled_touches_ = 0;  // touches recorded after a stable contact
  bool pressed_ = false;
  PressTarget target_;
  double height_ = 0;
  std::optional<double> first_contact_;  // sensor height when the gel first met the object
};

}  // namespace touchcloud::simulation
