// The touch's motion frame by frame: what a touch that never settles says.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "touchcloud/error.hpp"
#include "touchcloud/simulation/motion/touch_motion.hpp"

namespace touchcloud::simulation {
namespace {

// 1 mm per frame, in contact from the first frame: frame k is k mm past
// first contact.
RobotSpec robot() {
  RobotSpec r;
  r.speed_mm_s = 30.0;
  r.press_depth_mm = 1.5;
  r.max_contact_depth_mm = 10.0;
  return r;
}

// Steps a touch, in contact every frame, that settles on frame `stable_at`
// (never if negative), until its recorded frame, which it returns.
TouchStep touch(TouchMotion& motion, int stable_at) {
  for (int frame = 0;; ++frame) {
    const TouchStep step = motion.next(PressTarget(1.0, 2.0), 50.0, stable_at >= 0 && frame == stable_at + 1);
    motion.observe_overlap(true);
    if (step.pressed) return step;
    if (frame > 100) throw std::logic_error("the touch did not end");
  }
}

std::string failure(TouchMotion& motion) {
  try {
    touch(motion, -1);
  } catch (const RunError& e) {
    return e.what();
  }
  return "the touch was recorded";
}

TEST(TouchMotion, ASettledTouchIsRecordedOneFrameAfterItsStableContactPressedFurther) {
  TouchMotion motion(robot(), 30.0);
  const TouchStep step = touch(motion, 4);
  EXPECT_EQ(step.frame_in_touch, 5);
  EXPECT_NEAR(motion.travel_past_contact_mm(), 4.0 + 1.5, 1e-12);
}

TEST(TouchMotion, AFirstTouchThatNeverSettlesIsAnErrorThatAsksAboutTheWiring) {
  TouchMotion motion(robot(), 30.0);
  const std::string m = failure(motion);
  EXPECT_NE(m.find("touch 0 at (1, 2) mm: the sensor is 11 mm past first contact"), std::string::npos) << m;
  EXPECT_NE(m.find("max_contact_depth_mm = 10"), std::string::npos) << m;
  EXPECT_NE(m.find("no stable contact in this run (is input 'contact' wired"), std::string::npos) << m;
}

TEST(TouchMotion, ATouchThatNeverSettlesAfterOthersDidBlamesTheContactNotTheWiring) {
  TouchMotion motion(robot(), 30.0);
  touch(motion, 4);
  touch(motion, 6);
  const std::string m = failure(motion);
  EXPECT_NE(m.find("touch 2 at (1, 2) mm: the sensor is 11 mm past first contact"), std::string::npos) << m;
  EXPECT_NE(m.find("although 2 earlier touch(es) of the run settled"), std::string::npos) << m;
  EXPECT_EQ(m.find("wired"), std::string::npos) << m;
}

}  // namespace
}  // namespace touchcloud::simulation
