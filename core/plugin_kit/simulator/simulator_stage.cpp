#include "touchcloud/plugin_kit/simulator_stage.hpp"

#include <sstream>

#include "touchcloud/types/contact_state.hpp"
#include "touchcloud/types/frames.hpp"
#include "touchcloud/types/tactile_cloud.hpp"
#include "touchcloud/types/touch.hpp"

namespace touchcloud::simulation {

namespace {

// What a scene's sensor is, in the words of its sensor section.
std::string sensor_kind(const Scene& scene) {
  if (scene.family == sensor::SensorFamily::GelSight) return "a GelSight-type sensor (sensor.family gelsight)";
  if (scene.sensor.pattern == sensor::GelPattern::ColourPattern)
    return "a colour-pattern GelStereo (sensor.pattern colour_pattern)";
  return "a GelStereo with markers (sensor.family gelstereo, sensor.pattern markers)";
}

}  // namespace

const char* simulator_stage_for(const Scene& scene) {
  if (scene.family == sensor::SensorFamily::GelSight) return "gelsight_simulator";
  if (scene.sensor.pattern == sensor::GelPattern::ColourPattern) return "colour_gelstereo_simulator";
  return "marker_gelstereo_simulator";
}

void SimulatorParameters::declare(ParameterSet& p) {
  p.add("scene", scene_file_, std::string()).input_file().doc("scene file (YAML): object, sensor, robot, effects");
  p.add("speed_mm_s", speed_mm_s_).unit("mm/s").above(0)
      .doc("descent speed once the gel touches (not set: the scene's robot.speed_mm_s)");
  p.add("approach_speed_mm_s", approach_speed_mm_s_).unit("mm/s").at_least(0)
      .doc("descent speed until the first frame with contact (0: speed_mm_s; not set: the scene's)");
  p.add("press_depth_mm", press_depth_mm_).unit("mm").at_least(0)
      .doc("further press after stable contact (not set: the scene's)");
  p.add("press_depth_range_mm", press_depth_range_mm_).unit("mm").range(0.0, 1000.0)
      .doc("[min, max]: each touch's further press drawn uniformly from it, keyed by --seed and the touch's "
           "number (a dataset of many press depths); instead of press_depth_mm");
  p.rule({"press_depth_range_mm", "press_depth_mm"}, [this]() -> std::optional<std::string> {
    if (!press_depth_range_mm_) return std::nullopt;
    if (press_depth_mm_) return "is set, and so is press_depth_mm: set one";
    if ((*press_depth_range_mm_)[0] > (*press_depth_range_mm_)[1]) return "has its minimum above its maximum";
    return std::nullopt;
  });
  p.add("safe_clearance_mm", safe_clearance_mm_).unit("mm").at_least(0)
      .doc("gel apex above the highest object point under the gel at the start (not set: the scene's)");
  p.add("max_contact_depth_mm", max_contact_depth_mm_).unit("mm").above(0)
      .doc("travel past first contact without stable contact that fails the run (not set: the scene's)");
  p.add("reach_tolerance_mm", reach_tolerance_mm_, 15.0).unit("mm").above(0)
      .doc("a pressed gel apex this far above the object's surface at the target means the gel could not "
           "reach it (a rim or the object's side under the gel): counted, warned, noted in summary.json");
  p.add("target_xy_mm", target_xy_mm_).unit("mm")
      .doc("[x, y] of the touch in the base frame when input 'target' is not wired");
}

void SimulatorParameters::declare_ports(PortSet& ports) {
  ports.optional_input<TouchTarget>("target", "where to touch (base frame, or the approach frame it carries: a touch from any side); else target_xy_mm");
  ports.optional_input<ContactState>("contact", "the previous frame's contact (wire stable_contact.state@previous)");
  ports.output<SensorPose>("pose", "the sensor pose the robot reports");
  ports.output<bool>("touch_done", "true on the recorded frame (stable contact, then the further press)");
  ports.metric("touch_frames", "frames", "camera frames of the touch, from the safe height to the recorded frame");
  ports.metric("press_travel_mm", "mm", "how far the sensor moved past first contact by the recorded frame");
  ports.metric("press_depth_mm", "mm", "the touch's further press after stable contact");
  ports.metric("apex_above_target_mm", "mm",
               "the pressed gel's apex above the object's surface at the target (about minus the press depth when "
               "the gel reached it)");
  ports.metric("unreachable_touches", "touches",
               "touches whose gel stopped more than reach_tolerance_mm above the surface at their target")
      .final()
      .lower_is_better();
  ports.metric("frames_simulated", "frames", "camera frames simulated").final();
  ports.metric("frames_rendered", "frames", "frames whose images were rendered").final();
  ports.metric("touches", "touches", "touches completed").final();
}

void SimulatorParameters::check(const char* stage) {
  scene_ = load_scene(scene_file_);
  if (const char* wanted = simulator_stage_for(scene_); std::string(wanted) != stage)
    throw ParameterError("scene", "the scene " + scene_.file.string() + " describes " + sensor_kind(scene_) +
                                      ", which plugin " + stage + " does not simulate: use plugin " + wanted);
  RobotSpec& r = scene_.robot;
  for (auto [value, field] : {std::pair{&speed_mm_s_, &r.speed_mm_s}, {&approach_speed_mm_s_, &r.approach_speed_mm_s},
                              {&press_depth_mm_, &r.press_depth_mm}, {&safe_clearance_mm_, &r.safe_clearance_mm},
                              {&max_contact_depth_mm_, &r.max_contact_depth_mm}})
    if (*value) *field = **value;
  r.press_depth_range_mm = press_depth_range_mm_;
  object_ = make_object_surface(scene_.object);
}

void SimulatorParameters::configure(RunContext& ctx) const {
  const RobotSpec& r = scene_.robot;
  ctx.used("speed_mm_s", r.speed_mm_s);
  ctx.used("approach_speed_mm_s", r.approach_speed_mm_s);
  ctx.used("press_depth_mm", r.press_depth_mm);
  ctx.used("safe_clearance_mm", r.safe_clearance_mm);
  ctx.used("max_contact_depth_mm", r.max_contact_depth_mm);
  ctx.note("effects", scene_.effects.str());
}

PressTarget SimulatorParameters::target(const StageIO& io) const {
  if (const auto* t = io.optional_input<TouchTarget>("target")) {
    if (target_xy_mm_) throw ParameterError("target_xy_mm", "is set, but input 'target' is wired too: use one");
    return {t->xy_mm, t->base_from_approach};
  }
  if (!target_xy_mm_)
    throw InputError("no touch target: wire input 'target' (a touch_target) or set target_xy_mm: [x, y]");
  return {{(*target_xy_mm_)[0], (*target_xy_mm_)[1]}};
}

const TouchFrame& SimulatorParameters::step(TouchSimulation& sim, const StageIO& io) const {
  const auto* contact = io.optional_input<ContactState>("contact");
  return sim.step(target(io), contact && contact->stable);
}

bool SimulatorParameters::frame_needs(const TouchSimulation& sim, const StageIO& io, const char* name) {
  return io.wants(name) && (!io.wanted_after_loop_only(name) || sim.frame().touch.pressed || io.final_call());
}

void SimulatorParameters::report(const TouchSimulation& sim, StageIO& io, RunContext& ctx) {
  const TouchFrame& f = sim.frame();
  SensorPose pose;
  pose.base_from_sensor = f.reported_base_from_sensor;
  if (io.wants("pose")) io.output("pose", pose);
  if (io.wants("touch_done")) io.output("touch_done", f.touch.pressed);
  if (!f.touch.pressed) return;
  ctx.metric("touch_frames", f.touch.frame_in_touch + 1, "frames");
  ctx.metric("press_travel_mm", f.travel_past_contact_mm, "mm");
  ctx.metric("press_depth_mm", sim.press_depth_mm(), "mm");
  // A touch whose gel stopped far above the surface at its target recorded
  // something else (a rim, the object's side): its points are not of the
  // target, and a surface fitted to them can swing far from the object.
  const double gap = sim.apex_above_target_surface_mm();
  ctx.metric("apex_above_target_mm", gap, "mm");
  if (gap <= reach_tolerance_mm_) return;
  ++unreachable_touches_;
  const TouchStep& touch = f.touch;
  std::ostringstream s;
  s << "warning: touch " << touch.touch << " at (" << touch.target.xy_mm.x() << ", " << touch.target.xy_mm.y()
    << ") mm did not reach the object's surface there: the pressed gel apex stopped " << gap
    << " mm above it (reach_tolerance_mm " << reach_tolerance_mm_
    << "); something higher under the gel, a rim or the object's side, was touched instead";
  ctx.log(s.str());
  ctx.note("unreachable_touch_" + std::to_string(touch.touch), s.str().substr(9));
}

void SimulatorParameters::report_run(const TouchSimulation& sim, RunContext& ctx) const {
  ctx.metric("unreachable_touches", static_cast<double>(unreachable_touches_), "touches");
  const SimulationCounts& c = sim.counts();
  ctx.metric("frames_simulated", static_cast<double>(c.frames_simulated), "frames");
  ctx.metric("frames_rendered", static_cast<double>(c.frames_rendered), "frames");
  ctx.metric("touches", static_cast<double>(c.touches_completed), "touches");
}

void declare_marker_truth(PortSet& ports) {
  ports.output<TactileCloudPtr>("tactile", "marker truth in the sensor frame, rest reference, displacements, "
                                           "reported pose");
  ports.output<CloudConstPtr>("truth_base", "marker truth in the base frame (true pose), mm");
  ports.metric("frames_projected", "frames", "frames whose marker pixels were computed").final();
  ports.metric("markers", "markers", "markers on the gel").final();
  ports.metric("marker_mean_spacing_mm", "mm", "mean distance from a marker to its nearest neighbour").final();
  ports.metric("marker_min_spacing_mm", "mm", "distance between the closest two markers").final();
  ports.metric("markers_seen_left", "markers", "markers of the gel at rest the left camera sees").final();
  ports.metric("markers_seen_right", "markers", "markers of the gel at rest the right camera sees").final();
  ports.metric("markers_seen_both", "markers", "markers of the gel at rest both cameras see").final();
}

std::unique_ptr<GelStereoSimulation> configure_gelstereo(const SimulatorParameters& touch, RunContext& ctx) {
  touch.configure(ctx);
  auto sim = std::make_unique<GelStereoSimulation>(touch.scene(), ctx.rng()(), touch.object());
  const MarkerLayout& layout = sim->markers();
  const StereoViews& rest = sim->rest_views();
  std::ostringstream s;
  s << layout.rest_mm.size() << " markers (mean spacing " << layout.mean_spacing_mm << " mm, min "
    << layout.min_spacing_mm << " mm); seen at rest: left " << rest.left.size() << ", right " << rest.right.size()
    << ", both " << rest.seen_by_both() << "; effects: " << sim->scene().effects.str();
  ctx.log(s.str());
  return sim;
}

void output_marker_truth(const GelStereoSimulation& sim, StageIO& io) {
  if (io.wants("tactile")) io.output<TactileCloudPtr>("tactile", std::make_shared<TactileCloud>(sim.truth_tactile()));
  if (io.wants("truth_base")) io.output<CloudConstPtr>("truth_base", sim.truth_base());
}

void report_markers(const GelStereoSimulation& sim, RunContext& ctx) {
  ctx.metric("frames_projected", static_cast<double>(sim.counts().frames_projected), "frames");
  const MarkerLayout& layout = sim.markers();
  ctx.metric("markers", static_cast<double>(layout.rest_mm.size()), "markers");
  ctx.metric("marker_mean_spacing_mm", layout.mean_spacing_mm, "mm");
  ctx.metric("marker_min_spacing_mm", layout.min_spacing_mm, "mm");
  ctx.metric("markers_seen_left", static_cast<double>(sim.rest_views().left.size()), "markers");
  ctx.metric("markers_seen_right", static_cast<double>(sim.rest_views().right.size()), "markers");
  ctx.metric("markers_seen_both", static_cast<double>(sim.rest_views().seen_by_both()), "markers");
}

}  // namespace touchcloud::simulation
