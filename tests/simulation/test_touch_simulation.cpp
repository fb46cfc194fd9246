// The touch written once for every family (touch_simulation.hpp): the same
// robot moves a GelStereo's dome and a GelSight's pad through the same
// frames, each stopping where its own gel meets the object.
#include <gtest/gtest.h>

#include <vector>

#include "sim_fixture.hpp"
#include "touchcloud/simulation/gelsight_simulation.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

// The plane is 10 mm up; each gel's outermost point (the dome's apex, the
// pad's face) starts 2.1 mm above it and descends 0.2 mm per frame (6 mm/s
// at 30 fps): frame k overlaps by 0.2 k - 2.1 mm, first contact at k = 11.
// The loop below stands in for stable_contact: it calls the contact stable
// once the sensor is 3.9 mm past first contact (4.0 mm at k = 31), so frame
// 32 is pressed 1.5 mm further: 5.5 mm past first contact, 5.6 mm into the
// plane, 33 frames, as marker_gelstereo_simulator's touch with stable_contact.
constexpr int kFramesPerTouch = 33;
constexpr double kPressTravelMm = 5.5;
const std::string kRobot = "robot: {speed_mm_s: 6, press_depth_mm: 1.5, safe_clearance_mm: 2.1}\n";

struct FrameSeen {
  int touch, frame_in_touch;
  bool pressed;
  double timestamp_s, travel_mm, apex_mm;
};

// One touch at `target`, and the first frame of the next.
std::vector<FrameSeen> touch(simulation::TouchSimulation& sim, const simulation::PressTarget& target) {
  std::vector<FrameSeen> seen;
  bool stable = false;
  for (int i = 0; i <= kFramesPerTouch; ++i) {
    const simulation::TouchFrame& f = sim.step(target, stable);
    seen.push_back({f.touch.touch, f.touch.frame_in_touch, f.touch.pressed, f.timestamp_s, f.travel_past_contact_mm,
                    sim.apex_above_target_surface_mm()});
    stable = f.travel_past_contact_mm >= 3.9;
  }
  return seen;
}

}  // namespace

TEST(TouchSimulation, TheSameRobotMovesEveryFamilysGelThroughTheSameFrames) {
  TempDir dir;
  simulation::GelStereoSimulation dome(plane_scene(dir, "[contact]", kRobot), 1);
  write_file(dir / "pad.yaml", "object: " + kPlaneObject + "\nsensor: {family: gelsight, fps: 30}\n" + kRobot +
                                   "effects: [contact]\n");
  simulation::GelSightSimulation pad(simulation::load_scene(dir / "pad.yaml"), 1);

  const auto a = touch(dome, {3, -2}), b = touch(pad, {3, -2});
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(a[i].touch, b[i].touch);
    EXPECT_EQ(a[i].frame_in_touch, b[i].frame_in_touch);
    EXPECT_EQ(a[i].pressed, b[i].pressed);
    EXPECT_EQ(a[i].timestamp_s, b[i].timestamp_s);
    EXPECT_NEAR(a[i].travel_mm, b[i].travel_mm, 1e-12);
    EXPECT_NEAR(a[i].apex_mm, b[i].apex_mm, 1e-9);
  }
  // The course itself: the start clear of the plane, first contact at frame
  // 11, the recorded frame 32 pressed 5.5 mm past it, then the next touch.
  EXPECT_NEAR(a[0].apex_mm, 2.1, 1e-9);
  EXPECT_EQ(a[10].travel_mm, 0.0);
  EXPECT_NEAR(a[12].travel_mm, 0.2, 1e-9);
  for (int k = 0; k < kFramesPerTouch - 1; ++k) EXPECT_FALSE(a[k].pressed) << k;
  EXPECT_TRUE(a[kFramesPerTouch - 1].pressed);
  EXPECT_NEAR(a[kFramesPerTouch - 1].travel_mm, kPressTravelMm, 1e-9);
  EXPECT_NEAR(a[kFramesPerTouch - 1].apex_mm, -(kPressTravelMm + 0.1), 1e-9);
  EXPECT_EQ(a[kFramesPerTouch].touch, 1);
  EXPECT_EQ(a[kFramesPerTouch].frame_in_touch, 0);
  EXPECT_EQ(dome.counts().touches_completed, 1);
  EXPECT_EQ(pad.counts().touches_completed, 1);
  EXPECT_EQ(pad.counts().frames_simulated, kFramesPerTouch + 1);
}

// Each family keeps its own camera's frame rate: the pad's default 25 fps
// makes the robot's steps 6/25 mm and its frames 40 ms apart.
TEST(TouchSimulation, EachFamilyStepsAtItsOwnCamerasFrameRate) {
  TempDir dir;
  write_file(dir / "pad.yaml", "object: " + kPlaneObject + "\nsensor: {family: gelsight}\n" + kRobot +
                                   "effects: [contact]\n");
  simulation::GelSightSimulation pad(simulation::load_scene(dir / "pad.yaml"), 1);
  const auto& start = pad.step({0, 0}, false);
  const double z0 = start.touch.base_from_sensor.translation().z();
  const auto& next = pad.step({0, 0}, false);
  EXPECT_DOUBLE_EQ(next.timestamp_s, 1.0 / 25.0);
  EXPECT_NEAR(z0 - next.touch.base_from_sensor.translation().z(), 6.0 / 25.0, 1e-12);
}
