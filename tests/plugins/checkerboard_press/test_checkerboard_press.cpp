// checkerboard_press: the stage yields its presses one per iteration, and
// refuses a loop longer than its presses (the presses themselves:
// tests/simulation/board/test_board_press.cpp).
#include "pipeline_fixture.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

class CheckerboardPressStage : public touchcloud::test::PipelineFixture {};

TEST_F(CheckerboardPressStage, YieldsOnePressPerIterationUntilTheLast) {
  const auto sensor_file = (test::source_dir() / "sample_clouds/gelstereo_palm2/sensor_true.yaml").string();
  Pipeline p = load("stages:\n  - id: l\n    loop:\n      max_iterations: 10\n      until: press.last_press\n"
                    "      stages:\n        - id: press\n          plugin: checkerboard_press\n"
                    "          params: {sensor: " + sensor_file + ", presses: [0, 0, 6, 20, 0, 8, 0, -15, 9]}\n");
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  ASSERT_EQ(r.loop_iterations.size(), 1u);
  EXPECT_EQ(r.loop_iterations[0].second, 3);
  const auto& seen = r.record.metrics.at("press.corners_seen").values;
  ASSERT_EQ(seen.size(), 3u);
  for (double s : seen) EXPECT_GT(s, 20);
}

TEST_F(CheckerboardPressStage, MorePressesAskedThanGivenIsAnError) {
  const auto sensor_file = (test::source_dir() / "sample_clouds/gelstereo_palm2/sensor_true.yaml").string();
  Pipeline p = load("stages:\n  - id: l\n    loop:\n      max_iterations: 3\n      stages:\n"
                    "        - id: press\n          plugin: checkerboard_press\n"
                    "          params: {sensor: " + sensor_file + ", random_presses: 2}\n");
  RunOptions o;
  o.quiet = true;
  try {
    run_pipeline(p, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_TRUE(std::string(e.what()).find("all 2 presses are used") != std::string::npos) << e.what();
  }
  const auto errors = this->errors("stages:\n  - id: press\n    plugin: checkerboard_press\n"
                                   "    params: {sensor: " + sensor_file + ", presses: [0, 0]}\n");
  ASSERT_FALSE(errors.empty());
  EXPECT_TRUE(mentions(errors[0], "tilt_x_deg, tilt_y_deg, depth_mm")) << errors[0].message;
}
