// gp_surface as a stage: touches of a known surface go in; the fitted mean
// follows the surface where it was touched, the factor is extended between
// selections, and the path each touch took is reported; a touch that adds
// nothing gives the same model again.
#include <cmath>

#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/surface_model.hpp"

using namespace touchcloud;

class GpSurfaceStage : public touchcloud::test::PipelineFixture {
 protected:
  RunResult run_touches(const std::string& gp_params, int touches) {
    Pipeline p = load(
        "stages:\n  - id: explore\n    loop:\n      max_iterations: " + std::to_string(touches) + "\n      stages:\n"
        "        - id: touch\n          plugin: test_patch_source\n"
        "          params: {centres_mm: [0, 0, 14, 0, 0, 14, 14, 14, 7, 7, 28, 7]}\n"
        "        - id: dedup\n          plugin: dedup\n          inputs: {cloud: touch.cloud}\n"
        "        - id: fit\n          plugin: gp_surface\n          params: " + gp_params + "\n"
        "          inputs: {cloud: dedup.added}\n"
        "        - id: sample\n          plugin: surface_sampler\n"
        "          params: {workspace_x_mm: [0, 14], workspace_y_mm: [0, 14], resolution: [15, 15]}\n"
        "          inputs: {surface: fit.surface}\n"
        "  - id: write\n    plugin: cloud_writer\n    params: {path: surface.pcd}\n    inputs: {cloud: sample.cloud}\n");
    RunOptions o;
    o.quiet = true;
    o.out_dir = dir_ / "out";
    return run_pipeline(p, o);
  }
};

TEST_F(GpSurfaceStage, MeanFollowsTheTouchedSurface) {
  const RunResult r = run_touches("{kernel: rbf}", 6);
  const PointCloud s = touchcloud::test::load_cloud(dir_ / "out/surface.pcd");
  ASSERT_EQ(s.size(), 225u);
  double worst = 0;
  for (const auto& p : s.points) worst = std::max(worst, std::abs(p.z - (10 + 3 * std::sin(p.x / 15.0) * std::cos(p.y / 20.0))));
  // The square [0, 14]^2 is covered by the touches: the GP interpolates a
  // smooth 3 mm relief there to well under a tenth of a millimetre.
  EXPECT_LT(worst, 0.05);
  const auto& n = r.record.metrics.at("fit.training_points").values;
  EXPECT_TRUE(std::is_sorted(n.begin(), n.end()));
  EXPECT_GT(n.back(), n.front());
}

TEST_F(GpSurfaceStage, ReportsSelectionsAndBorderedUpdates) {
  // With a huge growth threshold only the first touch selects; the rest
  // extend the factor. With 0 every touch selects again.
  RunResult r = run_touches("{reselect_growth: 100}", 5);
  auto paths = r.record.metrics.at("fit.update_path").values;
  EXPECT_EQ(paths.front(), 3);
  for (std::size_t i = 1; i < paths.size(); ++i) EXPECT_EQ(paths[i], 1) << i;
  EXPECT_EQ(r.record.metrics.at("fit.selections").values[0], 1);

  r = run_touches("{reselect_growth: 0, kernel: matern52}", 3);
  paths = r.record.metrics.at("fit.update_path").values;
  for (double p : paths) EXPECT_EQ(p, 3);
  for (double l : r.record.metrics.at("fit.lengthscale_mm").values) EXPECT_GT(l, 0);
}

TEST_F(GpSurfaceStage, SparseWithEveryPointInducingMatchesExact) {
  // The six patches hold fewer than 1,000 points, so method sparse takes
  // them all as inducing points and must give the exact stage's surface.
  run_touches("{kernel: rbf, reselect_growth: 100}", 6);
  const PointCloud exact = touchcloud::test::load_cloud(dir_ / "out/surface.pcd");
  const RunResult r = run_touches("{kernel: rbf, reselect_growth: 100, method: sparse, inducing_points: 1000}", 6);
  const PointCloud sparse = touchcloud::test::load_cloud(dir_ / "out/surface.pcd");
  ASSERT_EQ(sparse.size(), exact.size());
  double worst = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) worst = std::max(worst, double(std::abs(sparse[i].z - exact[i].z)));
  EXPECT_LT(worst, 1e-4);  // float PCD storage of z ~ 10 mm: ulp 1e-6
  const auto& n = r.record.metrics.at("fit.training_points").values;
  EXPECT_EQ(r.record.metrics.at("fit.inducing_points").values.back(), n.back());
}

TEST_F(GpSurfaceStage, SparseWithFewInducingPointsStillFollowsTheSurface) {
  const RunResult r = run_touches("{kernel: rbf, method: sparse, inducing_points: 60}", 6);
  EXPECT_EQ(r.record.metrics.at("fit.inducing_points").values.back(), 60);
  const PointCloud s = touchcloud::test::load_cloud(dir_ / "out/surface.pcd");
  double worst = 0;
  for (const auto& p : s.points) worst = std::max(worst, std::abs(p.z - (10 + 3 * std::sin(p.x / 15.0) * std::cos(p.y / 20.0))));
  EXPECT_LT(worst, 0.2);  // 60 points over a 14 mm square of a 3 mm relief
}

TEST(GpSurfaceModelOut, ATouchThatAddsNothingGivesTheSameModel) {
  touchcloud::test::StageHarness stage("gp_surface", {});
  stage.configure();
  const auto patch = [](double x0_mm) {
    auto cloud = std::make_shared<PointCloud>();
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) cloud->push_back(pcl::PointXYZ(x0_mm + i, j, 10 + 0.1f * i * j));
    return CloudConstPtr(cloud);
  };
  const auto fit = [&](CloudConstPtr cloud) { return stage.process_one<SurfaceModelPtr>({{"cloud", cloud}}, "surface"); };
  const SurfaceModelPtr first = fit(patch(0));
  const SurfaceModelPtr again = fit(CloudConstPtr(std::make_shared<PointCloud>()));
  EXPECT_EQ(again, first);
  EXPECT_EQ(stage.metric("update_path"), 0);
  const SurfaceModelPtr grown = fit(patch(8));
  EXPECT_NE(grown, first);
  EXPECT_EQ(grown->training_size(), 72u);
  EXPECT_EQ(first->training_size(), 36u);  // the earlier model is as it was
}
