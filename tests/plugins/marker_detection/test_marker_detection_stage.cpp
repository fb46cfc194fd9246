// The marker_detection stage in a pipeline, fed by the simulator's rendered
// frames, and its parameters.
#include "pipeline_fixture.hpp"

using namespace touchcloud;

namespace {

class MarkerDetectionStage : public touchcloud::test::PipelineFixture {
 protected:
  RunResult run(const std::string& detect_params) {
    write("object: {analytic: plane, height_mm: 10}\neffects: [refraction, render, pixel_noise, blur]\n",
          "scene.yaml");
    Pipeline p = load(
        "stages:\n"
        "  - id: sim\n"
        "    plugin: touch_simulator\n"
        "    params: {scene: scene.yaml, target_xy_mm: [0, 0]}\n"
        "  - id: detect\n"
        "    plugin: marker_detection\n"
        "    params: {" + detect_params + "}\n"
        "    inputs: {frame: sim.frame}\n");
    RunOptions o;
    o.quiet = true;
    return run_pipeline(p, o);
  }
};

}  // namespace

TEST_F(MarkerDetectionStage, FindsTheRenderedMarkersInBothViews) {
  const RunResult r = run("polarity: dark, diameter_px: [3, 12], contrast_grey: 30");
  const double left = r.record.metrics.at("detect.markers_left").values.at(0);
  const double right = r.record.metrics.at("detect.markers_right").values.at(0);
  EXPECT_GT(left, 1000);
  EXPECT_GT(right, 1000);
  // Looking for bright dots instead finds only a few pockets of gel between them.
  const RunResult bright = run("polarity: bright");
  EXPECT_LT(bright.record.metrics.at("detect.markers_left").values.at(0), 0.05 * left);
}

TEST_F(MarkerDetectionStage, ParametersAreChecked) {
  try {
    run("diameter_px: [12, 3]");
    ADD_FAILURE() << "ran with diameter_px [12, 3]";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("diameter_px"), std::string::npos) << e.what();
  }
  const auto d = errors(
      "stages:\n  - id: detect\n    plugin: marker_detection\n    params: {polarity: grey}\n");
  ASSERT_FALSE(d.empty());
  EXPECT_TRUE(touchcloud::test::mentions(d[0], "polarity")) << d[0].str();
}
