// next_touch in pipelines: random first touches then the variance decides,
// the footprint strategy and the space-filling start fixed by the seed, the
// workspace from the scene, and the refusals at validation; the choices
// themselves are tested in tests/core/sensing/planning.
#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

#include "pipeline_fixture.hpp"
#include "sim_fixture.hpp"
#include "touchcloud/simulation/objects/reach_check.hpp"
#include "touchcloud/simulation/scene/scene.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

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

// Touches that count: with the run's scene, the cells where the gel cannot
// reach the ring's table inside its hole are never chosen, every other cell
// is touched once, and the loop ends early on `plan.done` with a note.
TEST_F(NextTouchStage, CellsTheGelCannotReachAreNeverChosenAndTheLoopEndsWhenNoneIsLeft) {
  test::write_file(dir_ / "ring.obj", test::ring_obj());
  const auto made = test::run_program(test::binary_dir() / "bin" / "touchcloud-make-scene",
                                      {(dir_ / "ring.obj").string(), "--name", "ring", "--out", dir_.path().string()});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const fs::path scene_file = dir_ / "ring/scene.yaml";
  const simulation::Scene scene = simulation::load_scene(scene_file);
  const auto surface = simulation::make_object_surface(scene.object);
  const WorkspaceGrid& grid = scene.workspace;
  const std::vector<double> gaps = simulation::apex_gaps_mm(*surface, grid, 32.5);
  std::set<int> unreachable;
  for (int c = 0; c < grid.cells(); ++c)
    if (gaps[static_cast<std::size_t>(c)] > simulation::kDefaultReachToleranceMm) unreachable.insert(c);
  ASSERT_FALSE(unreachable.empty());

  Pipeline p = load("scene: ring/scene.yaml\nstages:\n  - id: l\n    loop:\n      max_iterations: 500\n"
                    "      until: plan.done\n      stages:\n        - id: plan\n          plugin: next_touch\n"
                    "          params: {strategy: random, initial_random: 1}\n");
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  const auto& cells = r.record.metrics.at("plan.cell").values;
  EXPECT_EQ(cells.size(), static_cast<std::size_t>(grid.cells()) - unreachable.size());
  std::set<int> chosen;
  for (const double c : cells) {
    EXPECT_FALSE(unreachable.count(static_cast<int>(c))) << "unreachable cell " << c << " chosen";
    chosen.insert(static_cast<int>(c));
  }
  EXPECT_EQ(chosen.size(), cells.size()) << "a cell chosen twice";
  EXPECT_EQ(r.record.metrics.at("plan.unreachable_cells").values.back(), static_cast<double>(unreachable.size()));
  EXPECT_EQ(r.record.metrics.at("plan.touches_planned").values.back(), static_cast<double>(cells.size()));
  EXPECT_EQ(r.record.metrics.at("plan.cells_left").values.back(), 0.0);
  ASSERT_TRUE(r.record.notes.count("plan.unreachable"));
  ASSERT_TRUE(r.record.notes.count("plan.stopped"));
  EXPECT_NE(r.record.notes.at("plan.stopped").find("no cell is left"), std::string::npos);
}

// With revisit, a cell whose touch added no point (the same patch again,
// de-duplicated to nothing) is not chosen again: the plane's variance keeps
// the far corner 49 first, so without the rule every touch would go there.
TEST_F(NextTouchStage, ACellWhoseTouchAddedNoPointIsNotChosenAgain) {
  Pipeline p = load(
      "stages:\n  - id: model\n    plugin: test_plane_surface\n    params: {peak_mm: [0, 0]}\n"
      "  - id: l\n    loop:\n      max_iterations: 5\n      stages:\n"
      "        - id: plan\n          plugin: next_touch\n"
      "          params: {workspace_x_mm: [0, 100], workspace_y_mm: [0, 50], grid: [10, 5], initial_random: 1,\n"
      "                   revisit: true}\n"
      "          inputs: {surface: model.surface, added: dedup.added@previous}\n"
      "        - id: patch\n          plugin: test_patch_source\n          params: {centres_mm: [0, 0]}\n"
      "        - id: dedup\n          plugin: dedup\n          inputs: {cloud: patch.cloud}\n");
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  const auto& cells = r.record.metrics.at("plan.cell").values;
  ASSERT_EQ(cells.size(), 5u);
  // Touch 0 (random) adds the patch; touch 1 goes to 49 and adds nothing, so
  // 49 is closed for touch 2, which takes 39 at (95, 35), then 29 at (95, 25).
  EXPECT_EQ(cells[1], 49);
  EXPECT_EQ(cells[2], 39);
  EXPECT_EQ(cells[3], 29);
  EXPECT_EQ(r.record.metrics.at("plan.cells_without_gain").values.back(), 3.0);
}
