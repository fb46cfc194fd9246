// The one lifecycle (stage.hpp), enforced by Stage itself: the runtime and
// the test harness drive a stage through the same calls, check runs once
// and before configure, process and finish need configure, and the rules
// between parameters are checked with the stage's own checks.
#include <gtest/gtest.h>

#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "test_support.hpp"

using namespace touchcloud;

TEST(StageLifecycle, TheHarnessRunsCheckOnceThroughConfigure) {
  test::StageHarness stage("test_counter", {});
  stage.configure();
  stage.process({}, {"value"});
  stage.finish();
  EXPECT_EQ(stage.metric("checks"), 1.0);
}

class StageLifecycleRun : public test::PipelineFixture {};

TEST_F(StageLifecycleRun, TheRuntimeChecksAtLoadAndDoesNotCheckAgainAtConfigure) {
  Pipeline p = load("stages:\n  - id: c\n    plugin: test_counter\n");
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(r.record.metrics.at("c.checks").values.back(), 1.0);
}

TEST(StageLifecycle, ProcessOrFinishBeforeConfigureIsRefused) {
  test::StageHarness stage("test_counter", {});
  EXPECT_THROW(stage.process({}, {"value"}), std::logic_error);
  EXPECT_THROW(stage.finish(), std::logic_error);
}

TEST(StageLifecycle, ABrokenRuleBetweenParametersStopsConfigureNamingTheParameter) {
  const std::string scene = std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/fox_mask/scene.yaml";
  test::StageHarness stage("checkerboard_press",
                           {{"sensor", scene}, {"depth_range_mm", std::vector<double>{10, 4}}});
  try {
    stage.configure();
    FAIL() << "a [min, max] with min > max was accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter(), "depth_range_mm");
    EXPECT_EQ(e.detail(), "must be [min, max] with min <= max");
  }
}
