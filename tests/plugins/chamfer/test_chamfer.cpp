// chamfer: hand-checked metrics in a small pipeline, a series per loop
// iteration, mesh ground truth, and validation of its parameters.
#include <cmath>

#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"

using namespace touchcloud;

namespace {

PointCloud cloud(std::initializer_list<std::array<float, 3>> points) {
  PointCloud c;
  for (const auto& p : points) c.push_back(pcl::PointXYZ(p[0], p[1], p[2]));
  return c;
}

}  // namespace

class Chamfer : public touchcloud::test::PipelineFixture {
 protected:
  void SetUp() override {
    // Ground truth: three points 10 mm apart on the x axis; the estimate 1 mm
    // above the first and 2 mm above the second. By hand: est -> gt 1.5 mm,
    // gt -> est (3 + sqrt(104)) / 3 mm, Hausdorff sqrt(104) mm, 95th
    // percentile est -> gt 2 mm (the larger of two); at 1.5 mm precision 1/2,
    // recall 1/3, F-score 0.4.
    test::save_pcd(dir_ / "gt.pcd", cloud({{0, 0, 0}, {10, 0, 0}, {20, 0, 0}}));
    test::save_pcd(dir_ / "est.pcd", cloud({{0, 0, 1}, {10, 0, 2}}));
  }
  RunResult run(const std::string& yaml) {
    Pipeline p = load(yaml);
    RunOptions o;
    o.quiet = true;
    return run_pipeline(p, o);
  }
  static std::string pipeline(const std::string& chamfer_params) {
    return "stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: est.pcd}\n"
           "  - id: score\n    plugin: chamfer\n    params: " + chamfer_params + "\n"
           "    inputs: {cloud: read.cloud}\n";
  }
  static const MetricSeries& series(const RunResult& r, const std::string& key) {
    const auto it = r.record.metrics.find(key);
    if (it == r.record.metrics.end()) throw std::runtime_error("no metric " + key);
    return it->second;
  }
};

TEST_F(Chamfer, HandCheckedMetricsOfACloud) {
  const RunResult r = run(pipeline("{ground_truth: gt.pcd}"));
  EXPECT_EQ(series(r, "score.chamfer_est_to_gt").values, std::vector<double>{1.5});
  EXPECT_EQ(series(r, "score.chamfer_est_to_gt").spec.unit, "mm");
  EXPECT_DOUBLE_EQ(series(r, "score.chamfer_gt_to_est").values.at(0), (3 + std::sqrt(104.0)) / 3);
  EXPECT_DOUBLE_EQ(series(r, "score.chamfer_symmetric").values.at(0), 0.5 * (1.5 + (3 + std::sqrt(104.0)) / 3));
  EXPECT_DOUBLE_EQ(series(r, "score.hausdorff").values.at(0), std::sqrt(104.0));
  EXPECT_DOUBLE_EQ(series(r, "score.fscore").values.at(0), 0.4);
  EXPECT_DOUBLE_EQ(series(r, "score.precision").values.at(0), 0.5);
  EXPECT_DOUBLE_EQ(series(r, "score.recall").values.at(0), 1.0 / 3);
  EXPECT_EQ(series(r, "score.fscore").spec.unit, "");
  EXPECT_EQ(r.record.metrics.count("score.fscore_threshold"), 0u) << "a parameter, not a result";
  EXPECT_DOUBLE_EQ(series(r, "score.p95_est_to_gt").values.at(0), 2.0);
  // The last item's local errors beside the final chamfer.
  EXPECT_DOUBLE_EQ(series(r, "score.final_p95_mm").values.at(0), 2.0);
  EXPECT_DOUBLE_EQ(series(r, "score.final_hausdorff_mm").values.at(0), std::sqrt(104.0));
  EXPECT_DOUBLE_EQ(series(r, "score.final_fscore").values.at(0), 0.4);
  EXPECT_EQ(series(r, "score.final_hausdorff_mm").spec.unit, "mm");
}

TEST_F(Chamfer, ThresholdAndMetricSelection) {
  const RunResult r = run(pipeline("{ground_truth: gt.pcd, fscore_threshold_mm: 2.5, metrics: 'chamfer_est_to_gt, fscore'}"));
  EXPECT_DOUBLE_EQ(series(r, "score.fscore").values.at(0), 0.8);  // P = 1, R = 2/3
  EXPECT_DOUBLE_EQ(series(r, "score.chamfer_est_to_gt").values.at(0), 1.5);
  EXPECT_EQ(r.record.metrics.count("score.hausdorff"), 0u);
  EXPECT_EQ(r.record.metrics.count("score.chamfer_gt_to_est"), 0u);
  EXPECT_EQ(r.record.metrics.count("score.final_hausdorff_mm"), 0u) << "not selected, not reported";
  EXPECT_EQ(r.record.metrics.count("score.final_p95_mm"), 0u);
  EXPECT_DOUBLE_EQ(series(r, "score.final_fscore").values.at(0), 0.8);
}

TEST_F(Chamfer, EachLoopIterationAddsToTheSeries) {
  const RunResult r = run(
      "stages:\n  - id: touches\n    loop:\n      max_iterations: 3\n      stages:\n"
      "        - id: read\n          plugin: cloud_reader\n          params: {path: est.pcd}\n"
      "        - id: score\n          plugin: chamfer\n          params: {ground_truth: gt.pcd}\n"
      "          inputs: {cloud: read.cloud}\n");
  EXPECT_EQ(series(r, "score.chamfer_est_to_gt").values, (std::vector<double>{1.5, 1.5, 1.5}));
}

TEST_F(Chamfer, MeshGroundTruthIsSampledOnce) {
  test::write_file(dir_ / "square.obj", "v 0 0 0\nv 100 0 0\nv 100 100 0\nv 0 100 0\nf 1 2 3 4\n");
  test::save_pcd(dir_ / "est.pcd", cloud({{50, 50, 2}, {20, 30, 2}, {70, 10, 2}}));
  const std::string params = "{ground_truth: square.obj, samples: 40000, metrics: chamfer_est_to_gt";
  const double a = series(run(pipeline(params + ", sample_seed: 3}")), "score.chamfer_est_to_gt").values.at(0);
  const double b = series(run(pipeline(params + ", sample_seed: 3}")), "score.chamfer_est_to_gt").values.at(0);
  const double c = series(run(pipeline(params + ", sample_seed: 4}")), "score.chamfer_est_to_gt").values.at(0);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // 2 mm above a plane sampled 4 per mm^2: 2 mm plus about 0.02 mm.
  EXPECT_GT(a, 2.0);
  EXPECT_LT(a, 2.1);
}

TEST_F(Chamfer, DeclaresACloudInAndAScoreOut) {
  const auto& schema = registry_.load("chamfer").schema();
  ASSERT_EQ(schema.inputs.size(), 1u);
  EXPECT_EQ(schema.inputs[0].name, "cloud");
  EXPECT_EQ(schema.inputs[0].type, "point_cloud");
  ASSERT_EQ(schema.outputs.size(), 1u);
  EXPECT_EQ(schema.outputs[0].name, "score");
  EXPECT_EQ(schema.outputs[0].type, "score");
}

// Beside the accuracy (Eq. 11), what it hides has a role too: the run's
// headline, the report and sweeps find it by role, never by name.
TEST_F(Chamfer, CompletenessFscoreAndCoverageAreDeclaredByRole) {
  std::map<std::string, MetricRole> roles;
  for (const auto& m : registry_.load("chamfer").schema().metrics) roles[m.name] = m.role;
  EXPECT_EQ(roles.at("chamfer_est_to_gt"), MetricRole::accuracy);
  EXPECT_EQ(roles.at("chamfer_gt_to_est"), MetricRole::completeness);
  EXPECT_EQ(roles.at("fscore"), MetricRole::fscore);
  EXPECT_EQ(roles.at("recall"), MetricRole::coverage);
}

TEST_F(Chamfer, BadParametersAreFoundBeforeTheRun) {
  test::write_file(dir_ / "garbage.stl", "not a mesh\n");
  const auto first_error = [&](const std::string& params) {
    const auto diags = errors(pipeline(params));
    return diags.empty() ? std::string() : diags[0].message;
  };
  EXPECT_NE(first_error("{ground_truth: missing.stl}").find("ground_truth"), std::string::npos);
  const std::string garbage = first_error("{ground_truth: garbage.stl}");
  EXPECT_NE(garbage.find("garbage.stl"), std::string::npos) << garbage;
  EXPECT_NE(garbage.find("not a readable stl mesh"), std::string::npos) << garbage;
  // Read at check, sampled only at configure: a mesh with nothing to sample
  // is still found before the run.
  test::write_file(dir_ / "flat.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n");
  const std::string flat = first_error("{ground_truth: flat.obj}");
  EXPECT_NE(flat.find("flat.obj: the mesh has no surface area to sample"), std::string::npos) << flat;
  const std::string metric = first_error("{ground_truth: gt.pcd, metrics: 'chamfer'}");
  EXPECT_NE(metric.find("unknown metric 'chamfer'"), std::string::npos) << metric;
  EXPECT_NE(first_error("{ground_truth: gt.pcd, fscore_threshold_mm: 0}").find("fscore_threshold_mm"),
            std::string::npos);
  EXPECT_NE(first_error("{ground_truth: gt.pcd, samples: -5}").find("samples"), std::string::npos);
}

// The scene's object is the ground truth, scaled and posed as the simulator
// places it: a 10 mm square at scale 5, lifted 7 mm, is the 50 mm square at
// z = 7, so an estimate on that square scores ~0 where the mesh file as it
// lies (at z = 0, 10 mm wide) would give ~7 mm and more.
TEST_F(Chamfer, TheScenesObjectIsTheGroundTruthScaledAndPosed) {
  test::write_file(dir_ / "square.obj", "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3 4\n");
  test::write_file(dir_ / "scene.yaml",
                   "object: {mesh: square.obj, scale: 5, pose: {xyz_mm: [0, 0, 7], rpy_deg: [0, 0, 0]}}\n");
  test::save_pcd(dir_ / "est.pcd", cloud({{45, 45, 7}, {5, 40, 7}, {25, 25, 7}}));
  const double placed =
      series(run(pipeline("{scene: scene.yaml, samples: 40000, metrics: chamfer_est_to_gt}")), "score.chamfer_est_to_gt")
          .values.at(0);
  EXPECT_LT(placed, 0.2);
  const double as_file =
      series(run(pipeline("{ground_truth: square.obj, samples: 40000, metrics: chamfer_est_to_gt}")),
             "score.chamfer_est_to_gt")
          .values.at(0);
  EXPECT_GT(as_file, 7.0);
}

// visible: from_above scores against what a press from above can reach of a
// closed cube (its top), and says so in its ground-truth record; the default
// keeps the whole surface and the record as it was.
TEST_F(Chamfer, FromAboveKeepsOnlyWhatAPressCanSee) {
  test::write_file(dir_ / "cube.obj", test::cube_obj(20));
  test::write_file(dir_ / "scene.yaml", "object: {mesh: cube.obj}\n");
  test::save_pcd(dir_ / "est.pcd", test::cube_top(20, 21));
  const RunResult all = run(pipeline("{scene: scene.yaml, samples: 24000}"));
  const RunResult above = run(pipeline("{scene: scene.yaml, samples: 24000, visible: from_above}"));
  EXPECT_LT(series(all, "score.recall").values.at(0), 0.3);
  EXPECT_GT(series(above, "score.recall").values.at(0), 0.99);
  const auto record = [](const RunResult& r) { return r.record.artifacts.at(0).attributes; };
  EXPECT_EQ(record(all).count("visible"), 0u);
  EXPECT_EQ(std::get<std::string>(record(above).at("visible")), "from_above");
  EXPECT_NEAR(static_cast<double>(std::get<std::int64_t>(record(above).at("hidden_points"))) / 24000, 5.0 / 6, 0.01);
  EXPECT_EQ(std::get<std::int64_t>(record(above).at("samples")), 24000);
}

TEST_F(Chamfer, SceneAndGroundTruthAreOneOrTheOther) {
  test::write_file(dir_ / "square.obj", "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3 4\n");
  test::write_file(dir_ / "scene.yaml", "object: {mesh: square.obj}\n");
  test::write_file(dir_ / "analytic.yaml", "object: {analytic: fox_mask}\n");
  test::write_file(dir_ / "no_object.yaml", "name: empty\n");
  const auto first_error = [&](const std::string& params) {
    const auto diags = errors(pipeline(params));
    return diags.empty() ? std::string() : diags[0].message;
  };
  EXPECT_NE(first_error("{}").find("give exactly one"), std::string::npos);
  EXPECT_NE(first_error("{scene: scene.yaml, ground_truth: gt.pcd}").find("give exactly one"), std::string::npos);
  const std::string analytic = first_error("{scene: analytic.yaml}");
  EXPECT_NE(analytic.find("analytic surface 'fox_mask'"), std::string::npos) << analytic;
  const std::string none = first_error("{scene: no_object.yaml}");
  EXPECT_NE(none.find("has no 'object:' section"), std::string::npos) << none;
  EXPECT_NO_THROW(load(pipeline("{scene: scene.yaml}")));
}
