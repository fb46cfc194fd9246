// pipelines/fox_mask_active.yaml and wave_surface_active.yaml, shortened:
// the surface gets closer to the CAD model as touches accumulate, the planner
// never repeats a cell, nothing is rendered, and a seed reproduces the run.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "test_support.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {
RunResult run_active(const std::string& pipeline, int touches, std::uint64_t seed, const fs::path& out,
                     const std::map<std::string, std::string>& extra = {}) {
  PluginRegistry registry;
  std::vector<Override> overrides = {{"explore.max_iterations", std::to_string(touches)},
                                     {"surface.resolution", "[80, 80]"}};
  for (const auto& [key, value] : extra) overrides.push_back({key, value});
  Pipeline p = Pipeline::load(test::source_dir() / "pipelines" / pipeline, overrides, registry);
  RunOptions o;
  o.seed = seed;
  o.out_dir = out;
  o.quiet = true;
  return run_pipeline(p, o);
}
const std::vector<double>& series(const RunResult& r, const std::string& key) { return r.record.metrics.at(key).values; }
}  // namespace

TEST(ActiveReconstruction, FoxMaskImprovesWithEveryFewTouches) {
  test::TempDir dir;
  const RunResult r = run_active("fox_mask_active.yaml", 12, 1, dir / "out");
  const auto& chamfer = series(r, "score.chamfer_est_to_gt");
  ASSERT_EQ(chamfer.size(), 12u);
  // After the 4 random touches the variance-driven ones keep improving the
  // surface; the GP of 12 touches is within a few millimetres of the mask.
  EXPECT_LT(chamfer.back(), 0.5 * chamfer.front()) << chamfer.front() << " -> " << chamfer.back();
  EXPECT_LT(chamfer.back(), 3.0);
  EXPECT_EQ(series(r, "score.final_chamfer_mm")[0], chamfer.back());
  const double converged = series(r, "score.convergence_touches")[0];
  EXPECT_GE(converged, 1);
  EXPECT_LE(converged, 12);

  const auto& cells = series(r, "plan.cell");
  EXPECT_EQ(std::set<double>(cells.begin(), cells.end()).size(), cells.size()) << "a cell was touched twice";
  EXPECT_EQ(series(r, "sensor.touches")[0], 12);
  EXPECT_EQ(series(r, "sensor.frames_rendered")[0], 0) << "a point-level pipeline renders no image";
  EXPECT_GT(series(r, "dedup.total_points").back(), 300);
  EXPECT_TRUE(fs::exists(dir / "out/fox_mask_surface.pcd"));
  EXPECT_TRUE(fs::exists(dir / "out/summary.json"));
}

TEST(ActiveReconstruction, SeededRunsAreIdentical) {
  test::TempDir dir;
  run_active("wave_surface_active.yaml", 6, 3, dir / "a");
  run_active("wave_surface_active.yaml", 6, 3, dir / "b");
  const std::string a = test::read_file(dir / "a/wave_surface_surface.pcd");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, test::read_file(dir / "b/wave_surface_surface.pcd"));
}

// The footprint-aware strategy with the space-filling start on the fox mask:
// seeded, the same cells and the same surface twice; every choice expected
// to leave less variance than there was, and none chosen twice.
TEST(ActiveReconstruction, FootprintStrategyRunsAreSeededAndReduceTheVariance) {
  test::TempDir dir;
  const std::map<std::string, std::string> fvr = {{"plan.strategy", "footprint_variance_reduction"},
                                                  {"plan.start", "space_filling"}};
  const RunResult a = run_active("fox_mask_active.yaml", 8, 5, dir / "a", fvr);
  const RunResult b = run_active("fox_mask_active.yaml", 8, 5, dir / "b", fvr);
  EXPECT_EQ(series(a, "plan.cell"), series(b, "plan.cell"));
  const std::string surface = test::read_file(dir / "a/fox_mask_surface.pcd");
  ASSERT_FALSE(surface.empty());
  EXPECT_EQ(surface, test::read_file(dir / "b/fox_mask_surface.pcd"));
  const auto& cells = series(a, "plan.cell");
  EXPECT_EQ(std::set<double>(cells.begin(), cells.end()).size(), cells.size());
  const auto& now = series(a, "plan.mean_variance");
  const auto& left = series(a, "plan.expected_mean_variance");
  ASSERT_EQ(left.size(), 4u) << "8 touches, the first 4 space-filling";
  for (std::size_t k = 0; k < left.size(); ++k) {
    EXPECT_TRUE(std::isfinite(left[k]) && left[k] >= 0) << k;
    EXPECT_LT(left[k], now[k]) << k;
  }
  EXPECT_LT(series(a, "score.chamfer_est_to_gt").back(), 3.0);
}

// pipelines/fox_mask_active_edges.yaml, whole (34 touches, the 200 x 200
// surface): the worst error stays under 5 mm where the main job's is 15 mm,
// at a better Eq. 11 than the main job's 0.79-0.93 mm. Seed 2, where the
// greatest-variance planner with the same surface left a tall part of the
// face untouched (Hausdorff 7.13 mm).
TEST(ActiveReconstruction, TheEdgesPipelineKeepsTheFoxMasksWorstErrorUnder5Mm) {
  test::TempDir dir;
  PluginRegistry registry;
  Pipeline p = Pipeline::load(test::source_dir() / "pipelines/fox_mask_active_edges.yaml", {}, registry);
  RunOptions o;
  o.seed = 2;
  o.out_dir = dir / "out";
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(series(r, "sensor.touches")[0], 34);
  EXPECT_LT(series(r, "score.hausdorff").back(), 5.0);
  EXPECT_LT(series(r, "score.chamfer_est_to_gt").back(), 0.79);
  EXPECT_GT(series(r, "score.fscore").back(), 0.95);
}
