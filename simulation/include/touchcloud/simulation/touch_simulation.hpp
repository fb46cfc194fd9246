// What every simulated sensor shares: the robot pressing the sensor's gel
// onto the scene's object, one camera frame per step(). The touch's course
// (motion/touch_motion.hpp), frame numbers and times, the reported pose
// (`pose_noise`), the touch's reach and the counts are here, written once;
// each family's gel and what it renders are in the classes derived from this
// one:
//
//   GelStereoSimulation  a hemispherical gel carrying markers, seen by two
//                        cameras through a plate (gelstereo_simulation.hpp)
//   GelSightSimulation   a flat pad under one camera (gelsight_simulation.hpp)
//
// Every random draw derives from `noise_seed` and the frame number alone.
//
// A touch from any side (a target with an approach frame) or on a turntable
// runs the same vertical press in its press frame: the object seen along the
// press (objects/approach_view.hpp), every family's gel pressed and rendered
// as from above; the pose and the base-frame points are mapped back to the
// object's frame (the base frame without a turntable).
#pragma once

#include <cstdint>
#include <memory>

#include <Eigen/Geometry>

#include "touchcloud/simulation/gel/gel_contact.hpp"
#include "touchcloud/simulation/motion/touch_motion.hpp"
#include "touchcloud/simulation/objects/approach_view.hpp"
#include "touchcloud/simulation/objects/object_surface.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"
#include "touchcloud/simulation/scene/scene.hpp"

namespace touchcloud::simulation {

struct TouchFrame {
  long index = 0;  // camera frame number in the run, from 0
  double timestamp_s = 0;
  TouchStep touch;
  double travel_past_contact_mm = 0;
  // The pose the robot reports (pose_noise applied), in the object's frame on
  // a turntable (the scene's base frame at angle 0), and the true one there.
  Eigen::Isometry3d reported_base_from_sensor = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d object_from_sensor = Eigen::Isometry3d::Identity();
};

struct SimulationCounts {
  long frames_simulated = 0;
  long frames_projected = 0;  // marker pixels computed (GelStereo)
  long frames_rendered = 0;
  long touches_completed = 0;
};

class TouchSimulation {
 public:
  virtual ~TouchSimulation() = default;
  TouchSimulation(const TouchSimulation&) = delete;
  TouchSimulation& operator=(const TouchSimulation&) = delete;

  const Scene& scene() const { return scene_; }
  const ObjectSurface& object() const { return *object_; }
  const SimulationCounts& counts() const { return counts_; }

  // The sensor origin's start height for a touch at `target` (of the
  // touch under way, or from above): the gel's outermost point (the dome's
  // apex, the pad's face) safe_clearance_mm above the highest object point
  // under the gel, in the press frame.
  double safe_height_mm(const PressTarget& target) const;
  // This frame's outermost gel point above the object's surface at the touch
  // target: about minus the press depth when the gel reached the target, far
  // above 0 when something higher under the gel (a rim, the object's side)
  // stopped it.
  double apex_above_target_surface_mm() const;
  // The further press of the touch under way, mm (robot.press_depth_range_mm draws one per touch).
  double press_depth_mm() const { return motion_.press_depth_mm(); }

  // Simulates the next frame (see TouchMotion for the touch's course): the
  // robot moves, the family's gel is pressed onto the object at the true
  // pose, and the pose the robot reports is drawn.
  const TouchFrame& step(const PressTarget& target, bool previous_stable);
  const TouchFrame& frame() const;  // RunError before the first step

 protected:
  // `object`: the scene's object surface when already built (a stage builds
  // it at check, where a bad mesh is bad input); null builds it here.
  // `pose_noise_stream`: the family's stream of pose draws.
  TouchSimulation(Scene scene, std::uint64_t noise_seed, std::shared_ptr<const ObjectSurface> object,
                  std::uint64_t pose_noise_stream);

  std::uint64_t noise_seed() const { return noise_seed_; }
  const GelContactOptions& contact() const { return contact_; }
  // What the gel is pressed onto: the object seen along the touch's press
  // (a touch from any side, a turntable), else object().
  const ObjectSurface& pressed_object() const { return view_ ? *view_ : *object_; }
  // The press frame in the object's frame; not set when it is the base
  // frame (a touch from above, no turntable).
  const std::optional<Eigen::Isometry3d>& object_from_press() const { return object_from_press_; }
  void count_rendered_frame() { ++counts_.frames_rendered; }
  void count_projected_frame() { ++counts_.frames_projected; }

 private:
  // The family's gel. Its extent across the press (a radius around the
  // sensor's axis that covers it) and the distance of its outermost point
  // from the sensor origin along the press.
  virtual double gel_footprint_radius_mm() const = 0;
  virtual double gel_reach_mm() const = 0;
  // Presses the gel onto pressed_object() with the sensor at
  // `press_from_sensor` (the true pose in the press frame); whether any of it
  // overlaps the object. Points kept in the base frame are mapped by
  // object_from_press() when set.
  virtual bool press(const Eigen::Isometry3d& press_from_sensor) = 0;
  // Forgets what was computed from the previous frame (pixels, hits).
  virtual void forget_frame() {}

  Scene scene_;
  std::uint64_t noise_seed_;
  std::uint64_t pose_noise_stream_;
  // Sets the press frame and the view for a touch starting at `target`.
  void start_press(const PressTarget& target);

  std::shared_ptr<const ObjectSurface> object_;
  std::shared_ptr<const scoring::TriangleMesh> mesh_;  // the placed mesh, read at the first touch that needs it
  std::unique_ptr<ApproachView> view_;
  std::optional<Eigen::Isometry3d> object_from_press_, base_from_press_;
  GelContactOptions contact_;
  TouchMotion motion_;
  TouchFrame frame_;
  bool has_frame_ = false;
  SimulationCounts counts_;
};

}  // namespace touchcloud::simulation
