// What the simulator stages (marker_gelstereo_simulator,
// colour_gelstereo_simulator, gelsight_simulator) share, declared once so
// that they name, check and report it alike: their parameter group (the
// scene file, the robot's values that override the scene's, where to touch,
// when a touch did not reach its target) with the inputs, outputs and
// metrics of the touch it governs; and the GelStereo stages' marker truth.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "touchcloud/parameters.hpp"
#include "touchcloud/ports.hpp"
#include "touchcloud/run_context.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"
#include "touchcloud/simulation/touch_simulation.hpp"

namespace touchcloud::simulation {

// The stage that simulates a scene's sensor: "marker_gelstereo_simulator",
// "colour_gelstereo_simulator" or "gelsight_simulator".
const char* simulator_stage_for(const Scene& scene);

class SimulatorParameters {
 public:
  // `scene`, the robot's `speed_mm_s`, `approach_speed_mm_s`,
  // `press_depth_mm`, `press_depth_range_mm`, `safe_clearance_mm`,
  // `max_contact_depth_mm`, then `reach_tolerance_mm` and `target_xy_mm`.
  void declare(ParameterSet& p);
  // Inputs `target` and `contact`; outputs `pose` and `touch_done`; the
  // metrics of each touch and of the run that report() and report_run() give.
  static void declare_ports(PortSet& ports);

  // At check: reads the scene, with the robot values set here in force, and
  // builds its object (an unreadable mesh is bad input, found by
  // `validate`); both are kept for configure. ParameterError naming `scene`
  // when the scene's sensor is simulated by another stage than `stage`.
  void check(const char* stage);
  const Scene& scene() const { return scene_; }
  std::shared_ptr<const ObjectSurface> object() const { return object_; }
  // At configure: records the robot values in force and the scene's effects.
  void configure(RunContext& ctx) const;

  // One frame of `sim`: towards input `target` or target_xy_mm, with the
  // contact input's verdict on the previous frame.
  const TouchFrame& step(TouchSimulation& sim, const StageIO& io) const;
  // Whether output `name` is to be made on the frame just stepped. Images
  // and their truth cost most of a frame: one that only stages after the
  // touch loop read (a dataset writer keeping the recorded frame) is made on
  // the recorded frame and on the loop's last call alone; its noise is keyed
  // by frame, so it is the same image either way.
  static bool frame_needs(const TouchSimulation& sim, const StageIO& io, const char* name);
  // Outputs `pose` and `touch_done`, and on the recorded frame the touch's
  // metrics and whether it reached its target.
  void report(const TouchSimulation& sim, StageIO& io, RunContext& ctx);
  // The run's metrics: touches, frames simulated and rendered, unreachable touches.
  void report_run(const TouchSimulation& sim, RunContext& ctx) const;

 private:
  PressTarget target(const StageIO& io) const;

  std::string scene_file_;
  // Not set: the scene's robot section says.
  std::optional<double> speed_mm_s_, approach_speed_mm_s_, press_depth_mm_, safe_clearance_mm_,
      max_contact_depth_mm_;
  std::optional<std::array<double, 2>> target_xy_mm_, press_depth_range_mm_;
  double reach_tolerance_mm_ = 15.0;

  Scene scene_;
  std::shared_ptr<const ObjectSurface> object_;
  long unreachable_touches_ = 0;
};

// The GelStereo stages' own (markers and colour pattern): outputs `tactile`
// and `truth_base`, the markers' truth, and the metrics of the marker layout
// and of what the cameras see of it at rest.
void declare_marker_truth(PortSet& ports);
// The GelStereo simulation of the scene `touch` read, its marker layout in the log.
std::unique_ptr<GelStereoSimulation> configure_gelstereo(const SimulatorParameters& touch, RunContext& ctx);
void output_marker_truth(const GelStereoSimulation& sim, StageIO& io);
void report_markers(const GelStereoSimulation& sim, RunContext& ctx);

}  // namespace touchcloud::simulation
