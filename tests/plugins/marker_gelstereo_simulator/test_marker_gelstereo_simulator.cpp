// The marker_gelstereo_simulator stage in pipelines: a touch on a plane at
// known height with stable_contact deciding, what gets computed for which
// outputs, seeds, overrides, failures, and the scenes of other sensors.
#include <cmath>
#include <sstream>

#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"
#include "sim_fixture.hpp"

using namespace touchcloud;

namespace {

// The plane is 10 mm up; the gel's apex starts 2.1 mm above it and descends
// 0.2 mm per frame (6 mm/s at 30 fps). Frame k overlaps by 0.2 k - 2.1 mm
// (less the top marker's few microns below the apex): first contact at k = 11,
// more than 2 mm from k = 21, stable (counter > 10) at k = 31, and frame 32
// is pressed 1.5 mm further: 5.6 mm into the plane, 5.5 mm past first contact.
constexpr int kFramesPerTouch = 33;
constexpr double kPenetrationMm = 5.6, kGelRadiusMm = 32.5;

std::string loop(const std::string& sim_params, const std::string& sim_inputs, const std::string& more_stages,
                 int max_iterations = 200) {
  return "pipeline: plane_touch\n"
         "stages:\n"
         "  - id: touch\n"
         "    loop:\n"
         "      max_iterations: " + std::to_string(max_iterations) + "\n"
         "      until: sim.touch_done\n"
         "      stages:\n"
         "        - id: sim\n"
         "          plugin: marker_gelstereo_simulator\n"
         "          params: {scene: scene.yaml" + sim_params + "}\n" +
         (sim_inputs.empty() ? "" : "          inputs: {" + sim_inputs + "}\n") + more_stages;
}

const std::string kContactStage =
    "        - id: contact\n"
    "          plugin: stable_contact\n"
    "          inputs: {tactile: sim.tactile}\n";
const std::string kTarget = ", target_xy_mm: [3, -2]";
const std::string kFromContact = "contact: contact.state@previous";
const std::string kWriteTruth =
    "  - id: write\n"
    "    plugin: cloud_writer\n"
    "    params: {path: truth.pcd}\n"
    "    inputs: {cloud: sim.truth_base}\n";
const std::string kSink =
    "        - id: sink\n"
    "          plugin: test_sim_sink\n"
    "          inputs: {frame: sim.frame, markers: sim.markers, pose: sim.pose}\n";

// The share of markers pressed onto the plane (z = 10 mm).
double share_on_plane(const PointCloud& truth) {
  std::size_t on_plane = 0;
  for (const auto& p : truth) on_plane += p.z < 10.0 + 1e-4;
  return static_cast<double>(on_plane) / static_cast<double>(truth.size());
}

class TouchPipeline : public touchcloud::test::PipelineFixture {
 protected:
  void scene(const std::string& effects) {
    write("object: {analytic: plane, height_mm: 10}\nrobot: {safe_clearance_mm: 2.1}\neffects: " + effects + "\n",
          "scene.yaml");
  }
  RunResult run(const std::string& yaml, std::uint64_t seed = 1, const std::vector<Override>& overrides = {}) {
    Pipeline p = load(yaml, overrides);
    RunOptions o;
    o.quiet = true;
    o.seed = seed;
    o.out_dir = dir_ / ("out" + std::to_string(runs_++));
    last_out_ = o.out_dir;
    return run_pipeline(p, o);
  }
  static double metric(const RunResult& r, const std::string& name) {
    auto it = r.record.metrics.find(name);
    if (it == r.record.metrics.end()) {
      ADD_FAILURE() << "no metric " << name;
      return -1;
    }
    return it->second.values.back();
  }
  int runs_ = 0;
  std::filesystem::path last_out_;
};

}  // namespace

TEST_F(TouchPipeline, APlaneTouchSettlesWhereEquationsTwoAndThreeSayAndRecordsMarkersOnThePlane) {
  scene("[contact]");
  const RunResult r = run(loop(kTarget, kFromContact, kContactStage) + kWriteTruth);
  EXPECT_EQ(r.loop_iterations.at(0).second, kFramesPerTouch);
  EXPECT_EQ(metric(r, "sim.frames_simulated"), kFramesPerTouch);
  EXPECT_EQ(metric(r, "sim.touches"), 1);
  EXPECT_EQ(metric(r, "sim.touch_frames"), kFramesPerTouch);
  EXPECT_NEAR(metric(r, "sim.press_travel_mm"), 5.5, 1e-9);
  EXPECT_EQ(metric(r, "contact.frames_to_stable"), kFramesPerTouch - 1);

  // The recorded frame: markers in contact lie on the plane, inside the cap
  // the rest gel would reach below it, and no marker lies below the plane.
  const PointCloud truth = touchcloud::test::load_cloud(last_out_ / "truth.pcd");
  const double cap_radius = std::sqrt(2 * kGelRadiusMm * kPenetrationMm - kPenetrationMm * kPenetrationMm);
  std::size_t on_plane = 0;
  for (const auto& p : truth) {
    ASSERT_GE(p.z, 10.0 - 1e-4);
    if (p.z < 10.0 + 1e-4) {
      ++on_plane;
      EXPECT_LE(std::hypot(p.x - 3.0, p.y + 2.0), cap_radius + 1e-3);
    }
  }
  // The cap holds its share of the dome's area, p / R, of the evenly spread markers.
  EXPECT_NEAR(share_on_plane(truth), kPenetrationMm / kGelRadiusMm, 0.015);
  EXPECT_GT(on_plane, 0u);
}

TEST_F(TouchPipeline, APipelineThatReadsOnlyTactileCloudsRendersAndProjectsNothing) {
  scene("[contact, refraction, lens_distortion, render, pixel_noise, blur, marker_dropout]");
  const RunResult r = run(loop(kTarget, kFromContact, kContactStage) + kWriteTruth);
  EXPECT_EQ(metric(r, "sim.frames_simulated"), kFramesPerTouch);
  EXPECT_EQ(metric(r, "sim.frames_projected"), 0);
  EXPECT_EQ(metric(r, "sim.frames_rendered"), 0);
  const std::string summary = touchcloud::test::read_file(last_out_ / "summary.json");
  EXPECT_NE(summary.find("\"sim.frames_rendered\""), std::string::npos);
}

TEST_F(TouchPipeline, APipelineThatReadsImagesGetsOneStereoFramePerCameraFrame) {
  scene("[contact, refraction, render]");
  const RunResult r = run(loop(kTarget, kFromContact, kContactStage + kSink));
  EXPECT_EQ(metric(r, "sim.frames_rendered"), kFramesPerTouch);
  EXPECT_EQ(metric(r, "sim.frames_projected"), kFramesPerTouch);
  EXPECT_EQ(metric(r, "sink.frames"), kFramesPerTouch);
  EXPECT_GT(metric(r, "sink.last_matches"), 1000);
  EXPECT_GT(metric(r, "sink.last_mean_grey"), 100);
}

// A writer after the touch loop keeps the recorded frame only: the images
// are rendered for that frame alone, and they are the very images the
// every-frame pipeline renders for it (the noise is keyed by frame).
TEST_F(TouchPipeline, ImagesReadOnlyAfterTheTouchAreRenderedForTheRecordedFrameAlone) {
  scene("[contact, refraction, render, pixel_noise, blur, marker_dropout, pose_noise]");
  const std::string after =
      "  - id: after\n"
      "    plugin: test_sim_sink\n"
      "    inputs: {frame: sim.frame, markers: sim.markers}\n";
  const RunResult every = run(loop(kTarget, kFromContact, kContactStage + kSink) + after, 5);
  const RunResult recorded = run(loop(kTarget, kFromContact, kContactStage) + after, 5);
  EXPECT_EQ(metric(every, "sim.frames_rendered"), kFramesPerTouch);
  EXPECT_EQ(metric(recorded, "sim.frames_rendered"), 1);
  EXPECT_EQ(metric(recorded, "sim.frames_simulated"), kFramesPerTouch);
  EXPECT_EQ(metric(recorded, "after.frames"), 1);
  EXPECT_EQ(metric(recorded, "after.image_hash"), metric(every, "after.image_hash"));
  EXPECT_EQ(metric(recorded, "after.marker_hash"), metric(every, "after.marker_hash"));
  // A loop that ends by its count before the touch is done still gives its last frame.
  const RunResult cut = run(loop(kTarget, kFromContact, kContactStage, 12) + after, 5);
  EXPECT_EQ(cut.loop_iterations.at(0).second, 12);
  EXPECT_EQ(metric(cut, "sim.frames_rendered"), 1);
  EXPECT_EQ(metric(cut, "after.frames"), 1);
}

// press_depth_range_mm draws each touch's further press: seeded, within the
// range, and pressed (the travel past first contact is the 4.0 mm to
// stable contact plus the drawn depth).
TEST_F(TouchPipeline, EachTouchPressesADepthDrawnFromTheRange) {
  scene("[contact]");
  const std::string yaml =
      "stages:\n  - id: touches\n    loop:\n      max_iterations: 4\n      stages:\n"
      "        - id: touch\n          loop:\n            max_iterations: 200\n            until: sim.touch_done\n"
      "            stages:\n"
      "              - id: sim\n                plugin: marker_gelstereo_simulator\n"
      "                params: {scene: scene.yaml, target_xy_mm: [3, -2], press_depth_range_mm: [0.5, 2.0]}\n"
      "                inputs: {contact: contact.state@previous}\n"
      "              - id: contact\n                plugin: stable_contact\n                inputs: {tactile: sim.tactile}\n";
  const RunResult a = run(yaml, 7), b = run(yaml, 7), c = run(yaml, 8);
  const auto& depths = a.record.metrics.at("sim.press_depth_mm").values;
  const auto& travel = a.record.metrics.at("sim.press_travel_mm").values;
  ASSERT_EQ(depths.size(), 4u);
  for (std::size_t i = 0; i < depths.size(); ++i) {
    EXPECT_GE(depths[i], 0.5);
    EXPECT_LE(depths[i], 2.0);
    EXPECT_NEAR(travel[i] - depths[i], 4.0, 1e-9) << "touch " << i;
  }
  EXPECT_NE(depths[0], depths[1]);
  EXPECT_EQ(b.record.metrics.at("sim.press_depth_mm").values, depths);
  EXPECT_NE(c.record.metrics.at("sim.press_depth_mm").values, depths);
  // One way to say the depth, and a range that is one.
  for (const auto& [overrides, why] : std::vector<std::pair<std::vector<Override>, std::string>>{
           {{{"sim.press_depth_mm", "1.0"}}, "is set, and so is press_depth_mm"},
           {{{"sim.press_depth_range_mm", "[2.0, 0.5]"}}, "has its minimum above its maximum"}}) {
    const auto diagnostics = errors(yaml, overrides);
    ASSERT_FALSE(diagnostics.empty()) << why;
    EXPECT_TRUE(touchcloud::test::mentions(diagnostics[0], why)) << diagnostics[0].str();
  }
}

TEST_F(TouchPipeline, ReadingImagesFromASceneWithoutRenderIsBadInput) {
  scene("[contact]");
  try {
    run(loop(kTarget, kFromContact, kContactStage + kSink));
    FAIL() << "images without the render effect";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no 'render' effect"), std::string::npos) << e.what();
  }
}

TEST_F(TouchPipeline, SeededRunsReproduceBitForBit) {
  scene("[contact, refraction, render, pixel_noise, blur, marker_dropout, pose_noise]");
  const std::string yaml = loop(kTarget, kFromContact, kContactStage + kSink);
  const RunResult a = run(yaml, 3), b = run(yaml, 3), c = run(yaml, 4);
  for (const char* m : {"sink.image_hash", "sink.marker_hash", "sink.pose_hash"}) {
    EXPECT_EQ(metric(a, m), metric(b, m)) << m;
    EXPECT_NE(metric(a, m), metric(c, m)) << m;
  }
}

TEST_F(TouchPipeline, ATouchWithoutStableContactFailsSayingWhere) {
  scene("[]");  // no contact effect: the markers never move, nothing settles
  try {
    run(loop(kTarget, kFromContact, kContactStage));
    FAIL() << "the touch went on forever";
  } catch (const RunError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("touch 0 at (3, -2) mm"), std::string::npos) << m;
    EXPECT_NE(m.find("past first contact"), std::string::npos) << m;
    EXPECT_NE(m.find("max_contact_depth_mm = 10"), std::string::npos) << m;
  }
}

TEST_F(TouchPipeline, AFastApproachSlowsAtFirstContactAndEndsInTheSamePress) {
  // At 30 mm/s (1 mm per frame) the apex is 1.1 and 0.1 mm above the plane
  // at frames 1 and 2 and 0.9 mm into it at frame 3, the first contact; from
  // there on 0.2 mm per frame: more than 2 mm from frame 9, stable at frame
  // 19, pressed at frame 20, 0.9 + 16 * 0.2 + 1.5 = 5.6 mm into the plane,
  // as deep as after the slow approach but in 21 frames instead of 33.
  scene("[contact]");
  const RunResult r = run(loop(kTarget, kFromContact, kContactStage) + kWriteTruth, 1,
                          {{"sim.approach_speed_mm_s", "30"}});
  EXPECT_EQ(r.loop_iterations.at(0).second, 21);
  EXPECT_EQ(metric(r, "contact.frames_to_stable"), 20);
  EXPECT_NEAR(metric(r, "sim.press_travel_mm"), 5.6 - 0.9, 1e-9);
  // The cap holds its share of the dome's area, p / R, of the evenly spread markers.
  EXPECT_NEAR(share_on_plane(touchcloud::test::load_cloud(last_out_ / "truth.pcd")), kPenetrationMm / kGelRadiusMm,
              0.015);
  // 0 keeps the descent speed all the way: the slow touch of the test above.
  EXPECT_EQ(run(loop(kTarget, kFromContact, kContactStage), 1, {{"sim.approach_speed_mm_s", "0"}})
                .loop_iterations.at(0).second,
            kFramesPerTouch);
}

TEST_F(TouchPipeline, RobotParametersOverrideTheScene) {
  scene("[contact]");
  const std::string yaml = loop(kTarget, kFromContact, kContactStage);
  const RunResult r = run(yaml, 1, {{"sim.press_depth_mm", "3.0"}});
  EXPECT_NEAR(metric(r, "sim.press_travel_mm"), 7.0, 1e-9);
  // What the run used is recorded: the override, and the scene's value for
  // each robot parameter left not set (the scene sets safe_clearance_mm).
  const auto& used = r.record.used.at("sim");
  EXPECT_EQ(used.at("press_depth_mm"), ParamValue(3.0));
  EXPECT_EQ(used.at("safe_clearance_mm"), ParamValue(2.1));
  try {
    run(yaml, 1, {{"sim.press_depth_mm", "-0.5"}});
    FAIL() << "a negative press depth was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("press_depth_mm"), std::string::npos) << e.what();
  }
}

TEST_F(TouchPipeline, NeedsATargetAndAReadableScene) {
  scene("[contact]");
  try {
    run(loop("", kFromContact, kContactStage));
    FAIL() << "no target";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no touch target"), std::string::npos) << e.what();
  }
  write("object: {mesh: absent.ply}\n", "scene.yaml");
  const auto diagnostics = errors(loop(kTarget, kFromContact, kContactStage));
  ASSERT_FALSE(diagnostics.empty());
  EXPECT_TRUE(touchcloud::test::mentions(diagnostics[0], "object.mesh")) << diagnostics[0].str();
}

// In the ring's hole the pressed gel stops on the rim, far above the table
// at the target: the touch is counted, warned about and noted; a touch on
// the ring's top is not.
TEST_F(TouchPipeline, ATouchThatCannotReachTheSurfaceAtItsTargetIsReported) {
  write(touchcloud::test::ring_obj(), "ring.obj");
  write("object: {mesh: ring.obj}\neffects: [contact]\n", "scene.yaml");
  const RunResult hole = run(loop(", target_xy_mm: [0, 0]", kFromContact, kContactStage));
  EXPECT_EQ(metric(hole, "sim.unreachable_touches"), 1);
  EXPECT_GT(metric(hole, "sim.apex_above_target_mm"), 30.0);
  ASSERT_EQ(hole.record.notes.count("sim.unreachable_touch_0"), 1u);
  EXPECT_NE(hole.record.notes.at("sim.unreachable_touch_0").find("did not reach the object's surface"),
            std::string::npos);

  const RunResult top = run(loop(", target_xy_mm: [30, 0]", kFromContact, kContactStage));
  EXPECT_EQ(metric(top, "sim.unreachable_touches"), 0);
  EXPECT_LT(metric(top, "sim.apex_above_target_mm"), 0.0);
  EXPECT_EQ(top.record.notes.count("sim.unreachable_touch_0"), 0u);
}

// A scene of another sensor is refused at check, so `touchcloud validate`
// says so, naming the plugin that simulates it.
TEST(MarkerGelStereoSimulator, RefusesTheScenesOfOtherSensorsNamingTheirPlugin) {
  touchcloud::test::expect_refuses_other_sensors("marker_gelstereo_simulator");
}
