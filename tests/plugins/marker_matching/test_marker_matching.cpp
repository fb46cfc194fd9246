// marker_matching on simulated marker pixels (the simulator's marker truth,
// with centre noise and dropout, anonymised and shuffled as a detector would
// report them): ids follow their markers through a press without a swap, and
// the stage's refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "anonymised_markers.hpp"
#include "stage_harness.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

TEST(MarkerMatchingStage, IdsFollowTheirMarkersThroughAPressAndOneViewMarkersStayUnpaired) {
  TempDir dir;
  const auto scene_file = write_scene(dir, kNoisyEffects);
  simulation::GelStereoSimulation sim(simulation::load_scene(scene_file), 7);
  test::StageHarness stage("marker_matching", {{"sensor", scene_file.string()}}, "match");
  stage.configure();
  std::mt19937_64 rng(2);
  std::map<int, int> true_id_of;  // stage id -> simulator marker id
  double deepest_travel = 0;
  for (int frame = 0; frame < 45; ++frame) {
    const auto& f = sim.step({3, -2}, false);  // keeps pressing: ~6 mm past first contact at the end
    deepest_travel = f.travel_past_contact_mm;
    const MarkerSet truth = sim.marker_set();
    const Anonymised a = anonymise(truth, rng);
    const auto out = stage.process_one<MarkerSetPtr>({{"markers", std::any(a.markers)}}, "markers");
    std::size_t swapped = 0;
    for (const auto& m : out->matches) {
      ASSERT_EQ(a.true_left[m.left], a.true_right[m.right]) << "frame " << frame;
      const auto [it, fresh] = true_id_of.emplace(m.id, a.true_left[m.left]);
      swapped += !fresh && it->second != a.true_left[m.left];
    }
    EXPECT_EQ(swapped, 0u) << "frame " << frame;
    // A marker found in both views this frame is paired unless its track was
    // lost (it fell out of a view earlier).
    EXPECT_GE(out->matches.size(), static_cast<std::size_t>(0.99 * truth.matches.size())) << "frame " << frame;
  }
  EXPECT_GT(deepest_travel, 2.0) << "the press never got deep";
  stage.finish();
  EXPECT_GT(stage.metric("reference_pairs"), 1400);
  // Dropout removes ~3% of each view: those markers are reported as one-view only.
  EXPECT_GT(stage.metric("left_only_mean"), 20);
  EXPECT_GT(stage.metric("right_only_mean"), 20);
}

TEST(MarkerMatchingStage, AReferenceFrameWithoutMarkersIsNamed) {
  TempDir dir;
  const auto scene_file = write_scene(dir, "[]");
  test::StageHarness stage("marker_matching", {{"sensor", scene_file.string()}});
  stage.configure();
  auto empty_left = std::make_shared<MarkerSet>();
  empty_left->right.push_back({{600, 300}, -1, 1});
  try {
    stage.process({{"markers", std::any(MarkerSetPtr(empty_left))}}, {"markers"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("reference"), std::string::npos) << m;
    EXPECT_NE(m.find("left view"), std::string::npos) << m;
  }
}

// A one-camera set (detection on one image) has no pairs to find; without
// the check the error did not say so (this test failed).
TEST(MarkerMatchingStage, OneCamerasMarkersAreRefusedByName) {
  TempDir dir;
  const auto scene_file = write_scene(dir, "[]");
  test::StageHarness stage("marker_matching", {{"sensor", scene_file.string()}});
  stage.configure();
  auto mono = std::make_shared<MarkerSet>();
  mono->views = {CameraView::Mono};
  mono->mono.push_back({{600, 300}, -1, 1});
  try {
    stage.process({{"markers", std::any(MarkerSetPtr(mono))}}, {"markers"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("input 'markers' holds one camera's markers (view mono)"), std::string::npos)
        << e.what();
  }
}

TEST(MarkerMatchingStage, ASensorFileThatDoesNotFitTheImagesIsNamed) {
  // The markers come from a sensor with a 30 mm baseline; the stage is told
  // 40 mm, so no prediction lands near a right marker.
  TempDir dir;
  const auto scene_file = write_scene(dir, "[contact, refraction]");
  simulation::GelStereoSimulation sim(simulation::load_scene(scene_file), 1);
  sim.step({0, 0}, false);
  const auto wrong_file = dir / "wrong_sensor.yaml";
  test::write_file(wrong_file, "sensor: {cameras: {baseline_mm: 40}}\n");
  test::StageHarness stage("marker_matching", {{"sensor", wrong_file.string()}});
  stage.configure();
  try {
    stage.process({{"markers", std::any(MarkerSetPtr(std::make_shared<MarkerSet>(sim.marker_set())))}}, {"markers"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("check the 'sensor' file"), std::string::npos) << e.what();
  }
}
