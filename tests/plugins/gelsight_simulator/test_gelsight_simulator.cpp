// gelsight_simulator as a stage: its image, height truth and tactile truth
// for the outputs read, and the scenes of other sensors it refuses.
#include "sim_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

TEST(GelSightSimulator, GivesTheImageAndTheTruthOfEachFrame) {
  TempDir dir;
  const auto scene = write_plane_scene(dir, "[contact, render]", "sensor: {family: gelsight}");
  StageHarness g("gelsight_simulator", {{"scene", scene.string()}, {"target_xy_mm", std::vector<double>{0, 0}}});
  g.configure();
  const auto out = g.process({}, {"image", "image_reference", "height_truth", "tactile", "touch_done"});
  EXPECT_EQ(std::any_cast<MonoColourFramePtr>(out.at("image"))->image.size(), cv::Size(320, 240));
  EXPECT_EQ(std::any_cast<MonoColourFramePtr>(out.at("image_reference"))->image.size(), cv::Size(320, 240));
  EXPECT_EQ(std::any_cast<HeightMapPtr>(out.at("height_truth"))->height_mm.size(), cv::Size(320, 240));
  // The pad's surface every truth_stride_px (8) pixels.
  EXPECT_EQ(std::any_cast<TactileCloudPtr>(out.at("tactile"))->points->size(), 40u * 30u);
  EXPECT_FALSE(std::any_cast<bool>(out.at("touch_done")));
  g.finish();
  EXPECT_EQ(g.metric("frames_simulated"), 1);
  EXPECT_EQ(g.metric("frames_rendered"), 1);
}

// A scene of another sensor is refused at check, so `touchcloud validate`
// says so, naming the plugin that simulates it.
TEST(GelSightSimulator, RefusesTheScenesOfOtherSensorsNamingTheirPlugin) {
  touchcloud::test::expect_refuses_other_sensors("gelsight_simulator");
}
