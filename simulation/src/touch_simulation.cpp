#include "touchcloud/simulation/touch_simulation.hpp"

#include "touchcloud/simulation/motion/pose_noise.hpp"

namespace touchcloud::simulation {

TouchSimulation::TouchSimulation(Scene scene, std::uint64_t noise_seed, std::shared_ptr<const ObjectSurface> object,
                                 std::uint64_t pose_noise_stream)
    : scene_(std::move(scene)),
      noise_seed_(noise_seed),
      pose_noise_stream_(pose_noise_stream),
      motion_(scene_.robot, scene_.fps(), noise_seed) {
  object_ = object ? std::move(object) : std::shared_ptr<const ObjectSurface>(make_object_surface(scene_.object));
  contact_.contact = scene_.effects.has(Effect::Contact);
  contact_.elastic_spread = scene_.effects.has(Effect::ElasticSpread);
  contact_.spread_sigma_mm = scene_.effect_parameters.spread_sigma_mm;
}

double TouchSimulation::safe_height_mm(const PressTarget& target) const {
  return object_->max_height_mm(target.xy_mm, gel_footprint_radius_mm()) + scene_.robot.safe_clearance_mm +
         gel_reach_mm();
}

double TouchSimulation::apex_above_target_surface_mm() const {
  const TouchFrame& f = frame();
  // The sensor's z points down (PressTarget::sensor_pose): the gel's
  // outermost point is gel_reach_mm below its origin.
  const double apex_z = f.touch.base_from_sensor.translation().z() - gel_reach_mm();
  return apex_z - object_->height_mm(f.touch.target.xy_mm);
}

const TouchFrame& TouchSimulation::step(const PressTarget& target, bool previous_stable) {
  const double start = motion_.touching() ? 0.0 : safe_height_mm(target);
  TouchFrame& f = frame_;
  f.touch = motion_.next(target, start, previous_stable);
  f.index = counts_.frames_simulated;
  f.timestamp_s = static_cast<double>(f.index) / scene_.fps();
  motion_.observe_overlap(press(f.touch.base_from_sensor));
  f.travel_past_contact_mm = motion_.travel_past_contact_mm();
  f.reported_base_from_sensor = f.touch.base_from_sensor;
  if (scene_.effects.has(Effect::PoseNoise))
    f.reported_base_from_sensor = noisy_pose(f.touch.base_from_sensor, scene_.effect_parameters, noise_seed_,
                                             pose_noise_stream_, static_cast<std::uint64_t>(f.index));
  ++counts_.frames_simulated;
  if (f.touch.pressed) ++counts_.touches_completed;
  has_frame_ = true;
  forget_frame();
  return f;
}

const TouchFrame& TouchSimulation::frame() const {
  if (!has_frame_) throw RunError("no frame has been simulated yet");
  return frame_;
}

}  // namespace touchcloud::simulation
