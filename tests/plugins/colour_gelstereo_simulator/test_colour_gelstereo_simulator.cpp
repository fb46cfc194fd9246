// colour_gelstereo_simulator as a stage: the colour pair, its reference and
// its dense truth for the outputs read, and the scenes of other sensors it
// refuses.
#include "colour_fixture.hpp"
#include "sim_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/colour_stereo_frame.hpp"
#include "touchcloud/types/dense_maps.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

TEST(ColourGelStereoSimulator, GivesThePairItsReferenceAndItsTruthOfEachFrame) {
  TempDir dir;
  const auto scene = dir / "colour.yaml";
  write_file(scene, "object: " + kPlaneObject + "\n" + kColourSensor + "effects: [contact, render]\n");
  StageHarness c("colour_gelstereo_simulator", {{"scene", scene.string()}, {"target_xy_mm", std::vector<double>{0, 0}}});
  c.configure();
  const auto out = c.process({}, {"colour_frame", "colour_reference", "dense_truth", "tactile", "touch_done"});
  const auto frame = std::any_cast<ColourStereoFramePtr>(out.at("colour_frame"));
  EXPECT_EQ(frame->left.size(), cv::Size(640, 360));
  EXPECT_EQ(frame->left.type(), CV_8UC3);
  EXPECT_EQ(std::any_cast<ColourStereoFramePtr>(out.at("colour_reference"))->right.size(), cv::Size(640, 360));
  EXPECT_EQ(std::any_cast<DenseMapsPtr>(out.at("dense_truth"))->depth_mm.size(), cv::Size(640, 360));
  // The gel's marker truth, for the stages that decide the contact.
  EXPECT_GT(std::any_cast<TactileCloudPtr>(out.at("tactile"))->points->size(), 1000u);
  EXPECT_FALSE(std::any_cast<bool>(out.at("touch_done")));
  c.finish();
  EXPECT_EQ(c.metric("frames_rendered"), 1);
  EXPECT_GT(c.metric("markers"), 1000);
}

// A scene of another sensor is refused at check, so `touchcloud validate`
// says so, naming the plugin that simulates it.
TEST(ColourGelStereoSimulator, RefusesTheScenesOfOtherSensorsNamingTheirPlugin) {
  touchcloud::test::expect_refuses_other_sensors("colour_gelstereo_simulator");
}
