// pipelines/fox_mask_active.yaml and wave_surface_active.yaml, shortened:
// the surface gets closer to the CAD model as touches accumulate, the planner
// never repeats a cell, nothing is rendered, and a seed reproduces the run.
#include <gtest/gtest.h>

#include <set>

#include "test_support.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {
RunResult run_active(const std::string& pipeline, int touches, std::uint64_t seed, const fs::path& out) {
  PluginRegistry registry;
  Pipeline p = Pipeline::load(test::source_dir() / "pipelines" / pipeline,
                              {{"explore.max_iterations", std::to_string(touches)}, {"surface.resolution", "[80, 80]"}},
                              registry);
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
  EXPECT_TRUE(fs::exists(dir / "out/fox_mask_active_surface.pcd"));
  EXPECT_TRUE(fs::exists(dir / "out/summary.json"));
}

TEST(ActiveReconstruction, SeededRunsAreIdentical) {
  test::TempDir dir;
  run_active("wave_surface_active.yaml", 6, 3, dir / "a");
  run_active("wave_surface_active.yaml", 6, 3, dir / "b");
  const std::string a = test::read_file(dir / "a/wave_surface_active_surface.pcd");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, test::read_file(dir / "b/wave_surface_active_surface.pcd"));
}
