#include "touchcloud/simulation/motion/touch_motion.hpp"

#include <sstream>

#include "touchcloud/simulation/render/counter_random.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::simulation {

Eigen::Isometry3d PressTarget::sensor_pose(double height_mm) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(xy_mm.x(), xy_mm.y(), height_mm);
  pose.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return pose;
}

bool PressTarget::operator==(const PressTarget& other) const {
  if (xy_mm != other.xy_mm || base_from_approach.has_value() != other.base_from_approach.has_value()) return false;
  return !base_from_approach || base_from_approach->matrix() == other.base_from_approach->matrix();
}

TouchStep TouchMotion::next(const PressTarget& target, double start_height_mm, bool previous_stable) {
  if (!target.xy_mm.allFinite() || (target.base_from_approach && !target.base_from_approach->matrix().allFinite()))
    throw RunError("the touch target is not finite");
  if (!touching_) {
    touching_ = true;
    ++touch_;
    frame_ = 0;
    pressed_ = false;
    target_ = target;
    height_ = start_height_mm;
    first_contact_.reset();
    press_depth_mm_ = robot_.press_depth_mm;
    if (const auto& range = robot_.press_depth_range_mm) {
      constexpr std::uint64_t kPressDepth = 21;  // the draw stream of press depths
      press_depth_mm_ = (*range)[0] + ((*range)[1] - (*range)[0]) *
                                          uniform_from(draw_key(seed_, {kPressDepth, static_cast<std::uint64_t>(touch_)}));
    }
  } else {
    if (!(target == target_)) {
      std::ostringstream s;
      s << "the touch target moved from (" << target_.xy_mm.x() << ", " << target_.xy_mm.y() << ") to ("
        << target.xy_mm.x() << ", " << target.xy_mm.y() << ") mm during touch " << touch_ << " (frame " << frame_ + 1
        << "); a new target is taken only after touch_done";
      throw RunError(s.str());
    }
    ++frame_;
    pressed_ = previous_stable;
    height_ -= previous_stable ? press_depth_mm_ : first_contact_ ? step_mm_ : approach_step_mm_;
  }
  TouchStep step;
  step.touch = touch_;
  step.frame_in_touch = frame_;
  step.pressed = pressed_;
  step.target = target_;
  step.press_from_sensor = target_.sensor_pose(height_);
  step.base_from_sensor = step.press_from_sensor;
  return step;
}

void TouchMotion::observe_overlap(bool overlapping) {
  if (overlapping && !first_contact_) first_contact_ = height_;
  if (pressed_) {
    touching_ = false;  // the recorded frame ends the touch
    ++settled_touches_;
    return;
  }
  if (travel_past_contact_mm() > robot_.max_contact_depth_mm) {
    std::ostringstream s;
    s << "touch " << touch_ << " at (" << target_.xy_mm.x() << ", " << target_.xy_mm.y() << ") mm: the sensor is "
      << travel_past_contact_mm() << " mm past first contact (frame " << frame_ << " of the touch, sensor origin at z = "
      << height_ << " mm), beyond max_contact_depth_mm = " << robot_.max_contact_depth_mm;
    // Once a touch has settled the wiring is known to work: what failed is
    // this contact, and the frames it would record are ones the pipeline
    // itself did not trust (recording them anyway put a mug's surface 15 mm
    // off), so the run still ends, naming the likely cause.
    if (settled_touches_ > 0)
      s << ", and the pipeline saw no stable contact in it, although " << settled_touches_
        << " earlier touch(es) of the run settled: the gel met something it could not settle on (an edge, a rim, "
           "a thin part), or the sensor's images lost the contact (raise max_contact_depth_mm, or make the "
           "stable-contact stage less strict)";
    else
      s << ", and the pipeline has reported no stable contact in this run (is input 'contact' wired to a "
           "stable-contact stage, and does the scene have the 'contact' effect?)";
    throw RunError(s.str());
  }
}

}  // namespace touchcloud::simulation
