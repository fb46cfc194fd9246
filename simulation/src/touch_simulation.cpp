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
  return pressed_object().max_height_mm(target.xy_mm, gel_footprint_radius_mm()) + scene_.robot.safe_clearance_mm +
         gel_reach_mm();
}

double TouchSimulation::apex_above_target_surface_mm() const {
  const TouchFrame& f = frame();
  // The sensor's z points down (PressTarget::sensor_pose): the gel's
  // outermost point is gel_reach_mm below its origin.
  const double apex_z = f.touch.press_from_sensor.translation().z() - gel_reach_mm();
  return apex_z - pressed_object().height_mm(f.touch.target.xy_mm);
}

void TouchSimulation::start_press(const PressTarget& target) {
  view_.reset();
  object_from_press_.reset();
  base_from_press_.reset();
  if (!target.base_from_approach && !scene_.turntable) return;  // from above, as the object stands
  if (scene_.object.kind != ObjectKind::Mesh)
    throw InputError(std::string("a touch from another side than above needs a mesh object; the scene ") +
                         scene_.file.string() + " has object " + to_string(scene_.object.kind),
                     scene_.object.where);
  if (target.base_from_approach && !target.base_from_approach->linear().isUnitary(1e-9))
    throw InputError("the touch target's approach frame is not a rigid transform (its rotation is not orthonormal)");
  if (!mesh_) mesh_ = std::make_shared<const scoring::TriangleMesh>(read_placed_object_mesh(scene_.object));
  const Eigen::Isometry3d base_from_press = target.base_from_approach.value_or(Eigen::Isometry3d::Identity());
  const Eigen::Isometry3d base_from_object =
      scene_.turntable ? scene_.turntable->base_from_object(motion_.touches_started()) : Eigen::Isometry3d::Identity();
  object_from_press_ = base_from_object.inverse() * base_from_press;
  base_from_press_ = base_from_press;
  view_ = std::make_unique<ApproachView>(*mesh_, object_from_press_->inverse());
}

const TouchFrame& TouchSimulation::step(const PressTarget& target, bool previous_stable) {
  if (!motion_.touching()) start_press(target);
  const double start = motion_.touching() ? 0.0 : safe_height_mm(target);
  TouchFrame& f = frame_;
  f.touch = motion_.next(target, start, previous_stable);
  f.index = counts_.frames_simulated;
  f.timestamp_s = static_cast<double>(f.index) / scene_.fps();
  const bool overlapping = press(f.touch.press_from_sensor);
  if (view_ && f.touch.press_from_sensor.translation().z() - gel_reach_mm() < view_->floor_mm())
    throw RunError("touch " + std::to_string(f.touch.touch) + " at (" + std::to_string(target.xy_mm.x()) + ", " +
                   std::to_string(target.xy_mm.y()) +
                   ") mm of its approach frame passed the object's far side: it misses the object and the table");
  motion_.observe_overlap(overlapping);
  f.travel_past_contact_mm = motion_.travel_past_contact_mm();
  if (object_from_press_) {
    f.touch.base_from_sensor = *base_from_press_ * f.touch.press_from_sensor;
    f.object_from_sensor = *object_from_press_ * f.touch.press_from_sensor;
  } else {
    f.object_from_sensor = f.touch.base_from_sensor;
  }
  f.reported_base_from_sensor = f.object_from_sensor;
  if (scene_.effects.has(Effect::PoseNoise))
    f.reported_base_from_sensor = noisy_pose(f.object_from_sensor, scene_.effect_parameters, noise_seed_,
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
