// next_touch in pipelines: random first touches then the variance decides,
// the footprint strategy and the space-filling start fixed by the seed, the
// workspace from the scene, and the refusals at validation; the choices
// themselves are tested in tests/core/sensing/planning.
#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

#include "pipeline_fixture.hpp"

using namespace touchcloud;

class NextTouchStage : public touchcloud::test::PipelineFixture {};

TEST_F(NextTouchStage, InitialTouchesAreRandomThenVarianceDecides) {
  // Variance grows with distance from (0, 0): after 2 random touches, the
  // far corner's cell 49 (centre (95, 45)).
  Pipeline p = load(
      "stages:\n  - id: model\n    plugin: test_plane_surface\n    params: {peak_mm: [0, 0]}\n"
      "  - id: l\n    loop:\n      max_iterations: 4\n      stages:\n"
      "        - id: plan\n          plugin: next_touch\n"
      "          params: {workspace_x_mm: [0, 100], workspace_y_mm: [0, 50], grid: [10, 5], initial_random: 2}\n"
      "          inputs: {surface: model.surface}\n");
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  const auto& cells = r.record.metrics.at("plan.cell").values;
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_NE(cells[0], cells[1]);
  EXPECT_EQ(cells[2], 49);
  EXPECT_EQ(cells[3], 39) << "49 is touched; cell 39 at (95, 35) is next farthest from (0, 0)";
  EXPECT_EQ(r.record.metrics.at("plan.chosen_variance").values.size(), 2u);
}

// The footprint strategy and the space-filling start, twice with one seed:
// the same cells. The plane's variance grows with the distance from (0, 0);
// a press covers a patch, so the first choice is not the far corner 49 that
// Eq. 10 takes, but a cell whose press takes in more of the variance.
TEST_F(NextTouchStage, FootprintStrategyAndSpaceFillingStartAreFixedByTheSeed) {
  const std::string yaml =
      "stages:\n  - id: model\n    plugin: test_plane_surface\n    params: {peak_mm: [0, 0], correlation_mm: 15}\n"
      "  - id: l\n    loop:\n      max_iterations: 6\n      stages:\n"
      "        - id: plan\n          plugin: next_touch\n"
      "          params: {workspace_x_mm: [0, 100], workspace_y_mm: [0, 50], grid: [10, 5], initial_random: 2,\n"
      "                   strategy: footprint_variance_reduction, start: space_filling}\n"
      "          inputs: {surface: model.surface}\n";
  std::vector<std::vector<double>> runs;
  for (int i = 0; i < 2; ++i) {
    Pipeline p = load(yaml);
    RunOptions o;
    o.quiet = true;
    o.seed = 11;
    const RunResult r = run_pipeline(p, o);
    runs.push_back(r.record.metrics.at("plan.cell").values);
    const auto& left = r.record.metrics.at("plan.expected_mean_variance").values;
    const auto& now = r.record.metrics.at("plan.mean_variance").values;
    ASSERT_EQ(left.size(), 4u);
    for (std::size_t k = 0; k < left.size(); ++k) {
      EXPECT_TRUE(std::isfinite(left[k]) && left[k] >= 0) << left[k];
      EXPECT_LT(left[k], now[k]);
    }
  }
  EXPECT_EQ(runs[0], runs[1]);
  ASSERT_EQ(runs[0].size(), 6u);
  EXPECT_EQ(std::set<double>(runs[0].begin(), runs[0].end()).size(), 6u) << "no cell twice";
  EXPECT_NE(runs[0][2], 49) << "Eq. 10's corner";
}

TEST_F(NextTouchStage, AOneCellWorkspaceIsRefusedAtValidation) {
  const auto d = errors("stages:\n  - id: plan\n    plugin: next_touch\n"
                        "    params: {workspace_x_mm: [0, 10], workspace_y_mm: [0, 10], grid: [1, 1]}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(touchcloud::test::mentions(d[0], "parameter 'grid'")) << d[0].str();
  EXPECT_TRUE(touchcloud::test::mentions(d[0], "choosing a touch needs at least 2 cells")) << d[0].str();
}

TEST_F(NextTouchStage, EmptyWorkspaceIsRefusedAtValidation) {
  // Along x with max equal to min, along y with max below min.
  for (const std::string& bad : {std::string("workspace_x_mm: [10, 10], workspace_y_mm: [0, 10]"),
                                 std::string("workspace_y_mm: [20, 10], workspace_x_mm: [0, 10]")}) {
    const auto d = errors("stages:\n  - id: plan\n    plugin: next_touch\n    params: {" + bad + ", grid: [2, 2]}\n");
    ASSERT_EQ(d.size(), 1u) << bad;
    const std::string parameter = bad.substr(0, bad.find(':'));
    EXPECT_TRUE(touchcloud::test::mentions(d[0], "parameter '" + parameter + "': the workspace is empty")) << d[0].str();
    EXPECT_EQ(d[0].where.line, 4) << bad;
  }
}

// The workspace group: what the stage does not set comes from the scene's
// workspace: section (fox mask: [-60, 60] x [-60, 60], 14 x 14 cells), and
// summary.json records those values; with neither, validation says what is
// missing.
TEST_F(NextTouchStage, TheWorkspaceComesFromTheSceneWhereTheStageDoesNotSetIt) {
  const std::string scene = std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/fox_mask/scene.yaml";
  Pipeline p = load("stages:\n  - id: plan\n    plugin: next_touch\n"
                    "    params: {scene: " + scene + ", workspace_y_mm: [0, 12], initial_random: 1}\n");
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  const auto& used = r.record.used.at("plan");
  EXPECT_EQ(used.at("workspace_x_mm"), ParamValue(std::vector<double>{-60, 60}));
  EXPECT_EQ(used.at("grid"), ParamValue(std::vector<std::int64_t>{14, 14}));
  EXPECT_EQ(used.count("workspace_y_mm"), 0u) << "set by the stage, not taken from the scene";
  const int cell = static_cast<int>(r.record.metrics.at("plan.cell").values.at(0));
  EXPECT_TRUE(cell >= 0 && cell < 14 * 14) << cell;

  const auto d = errors("stages:\n  - id: plan\n    plugin: next_touch\n    params: {workspace_x_mm: [0, 10]}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(touchcloud::test::mentions(d[0], "the workspace needs workspace_y_mm, or a 'scene'")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 4);
}
