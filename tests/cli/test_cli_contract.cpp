// The CLI contract: exit statuses, error lines, --set, --seed, --out,
// and `plugins` output, exercised through the real binary.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cloud_files.hpp"
#include "test_support.hpp"

using touchcloud::test::read_file;
using touchcloud::test::run_cli;
using touchcloud::test::write_file;
namespace fs = std::filesystem;

namespace {
const std::string kDemo = (touchcloud::test::source_dir() / "pipelines/downsample_cloud.yaml").string();
const std::string kTestPlugins = "TOUCHCLOUD_PLUGIN_PATH=" TOUCHCLOUD_TEST_PLUGIN_DIR;

touchcloud::PointCloud cloud_of(std::initializer_list<std::array<float, 3>> points) {
  touchcloud::PointCloud c;
  for (const auto& p : points) c.push_back(pcl::PointXYZ(p[0], p[1], p[2]));
  return c;
}

bool has_line_starting(const std::string& text, const std::string& prefix) {
  std::size_t at = 0;
  while (at < text.size()) {
    if (text.compare(at, prefix.size(), prefix) == 0) return true;
    at = text.find('\n', at);
    if (at == std::string::npos) break;
    ++at;
  }
  return false;
}
}  // namespace

TEST(Cli, RunWritesOutputsAndSummary) {
  touchcloud::test::TempDir dir;
  const auto r = run_cli({"run", kDemo, "--out", (dir / "out").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out/gel_dome_thinned.ply"));
  const auto summary = nlohmann::json::parse(read_file(dir / "out/summary.json"));
  EXPECT_EQ(summary["pipeline"]["name"], "downsample_cloud");
  EXPECT_GT(summary["metrics"]["thin.points_out"]["value"].get<double>(), 0);
  EXPECT_LT(summary["metrics"]["thin.points_out"]["value"].get<double>(),
            summary["metrics"]["thin.points_in"]["value"].get<double>());
  EXPECT_NE(r.out.find("thin.points_out"), std::string::npos) << r.out;
}

TEST(Cli, SetOverridesAndSeedReproducesBitForBit) {
  touchcloud::test::TempDir dir;
  const std::vector<std::string> random = {"--set", "thin.method=random", "--set", "thin.keep_ratio=0.3", "--quiet"};
  auto args = [&](const std::string& out, const std::string& seed) {
    std::vector<std::string> a = {"run", kDemo, "--out", (dir / out).string(), "--seed", seed};
    a.insert(a.end(), random.begin(), random.end());
    return a;
  };
  ASSERT_EQ(run_cli(args("a", "5")).exit_code, 0);
  ASSERT_EQ(run_cli(args("b", "5")).exit_code, 0);
  ASSERT_EQ(run_cli(args("c", "6")).exit_code, 0);
  const std::string a = read_file(dir / "a/gel_dome_thinned.ply");
  EXPECT_EQ(a, read_file(dir / "b/gel_dome_thinned.ply"));
  EXPECT_NE(a, read_file(dir / "c/gel_dome_thinned.ply"));
  const auto summary = nlohmann::json::parse(read_file(dir / "a/summary.json"));
  EXPECT_EQ(summary["seed"], 5);
  EXPECT_EQ(summary["stages"][1]["params"]["keep_ratio"], 0.3);
  EXPECT_EQ(summary["metrics"]["thin.points_out"]["value"], 600);  // 30% of 2000
}

TEST(Cli, ValidateAcceptsAGoodPipeline) {
  const auto r = run_cli({"validate", kDemo});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("ok"), std::string::npos);
}

TEST(Cli, BadPipelinesExitTwoWithLocatedErrorsAndWriteNothing) {
  touchcloud::test::TempDir dir;
  const fs::path bad = dir / "bad.yaml";
  write_file(bad, "stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: missing.pcd}\n");
  for (const std::string verb : {"validate", "run"}) {
    std::vector<std::string> args = {verb, bad.string()};
    if (verb == "run") args.insert(args.end(), {"--out", (dir / "out").string()});
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << verb;
    EXPECT_TRUE(has_line_starting(r.err, bad.string() + ":4:20: error: ")) << r.err;
    EXPECT_TRUE(has_line_starting(r.err, "touchcloud: error: ")) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Cli, SetErrorsNameTheKey) {
  const auto r = run_cli({"validate", kDemo, "--set", "thin.leaf_size_mm=-3"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has_line_starting(r.err, "touchcloud: error: --set thin.leaf_size_mm=-3: ")) << r.err;
  EXPECT_NE(r.err.find("must be > 0 (mm)"), std::string::npos) << r.err;
  const auto r2 = run_cli({"validate", kDemo, "--set", "nonsense"});
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_TRUE(has_line_starting(r2.err, "touchcloud: error: --set 'nonsense' must be STAGE.PARAM=VALUE")) << r2.err;
}

TEST(Cli, SceneNamesTheObjectOfEveryStageAndAMismatchIsRefused) {
  const std::string fox = (touchcloud::test::source_dir() / "pipelines/fox_mask_active.yaml").string();
  const std::string wave = (touchcloud::test::source_dir() / "sample_clouds/wave_surface/scene.yaml").string();
  // The simulator alone on another object: the planner and the score would read the fox mask.
  const auto mismatch = run_cli({"validate", fox, "--set", "sensor.scene=" + wave});
  EXPECT_EQ(mismatch.exit_code, 2);
  EXPECT_TRUE(has_line_starting(mismatch.err, fox + ":")) << mismatch.err;
  EXPECT_NE(mismatch.err.find("stage 'score' (plugin chamfer) names the scene"), std::string::npos) << mismatch.err;
  EXPECT_NE(mismatch.err.find("but stage 'sensor' simulates " + wave), std::string::npos) << mismatch.err;
  const auto one_scene = run_cli({"validate", fox, "--scene", wave});
  EXPECT_EQ(one_scene.exit_code, 0) << one_scene.err;
  // run and sweep take it too: a scene that is not there is refused before anything runs.
  touchcloud::test::TempDir dir;
  const std::string missing = (dir / "no_scene.yaml").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", fox, "--scene", missing, "--out", (dir / "run").string()},
        std::vector<std::string>{"sweep", fox, "--scene", missing, "--vary", "dedup.threshold_mm=1.8", "--out",
                                 (dir / "sweep").string()}}) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args[0];
    EXPECT_NE(r.err.find("--scene " + missing + ": error: stage 'plan' (plugin next_touch), parameter 'scene': "
                         "input file " + missing + " does not exist"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "run"));
}

// A run is named after its scene too: "{scene}" in an output name becomes the
// scene's `name:`, summary.json records the scene, the report's title names
// it; without a scene "{scene}" is refused at validate.
TEST(Cli, OutputsAndTheReportAreNamedAfterTheRunsScene) {
  touchcloud::test::TempDir dir;
  touchcloud::test::save_pcd(dir / "est.pcd", cloud_of({{0, 0, 1}, {10, 0, 2}}));
  write_file(dir / "cup.yaml", "name: my_cup\n");
  const std::string body = "stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: est.pcd}\n"
                           "  - id: write\n    plugin: cloud_writer\n    params: {path: '{scene}_surface.pcd'}\n"
                           "    inputs: {cloud: read.cloud}\n";
  write_file(dir / "p.yaml", "pipeline: p\nscene: cup.yaml\n" + body);
  const auto r = run_cli({"run", (dir / "p.yaml").string(), "--out", (dir / "out").string(), "--report"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out/my_cup_surface.pcd"));
  const auto summary = nlohmann::json::parse(touchcloud::test::read_file(dir / "out/summary.json"));
  EXPECT_EQ(summary["scene"]["name"], "my_cup");
  EXPECT_EQ(summary["scene"]["file"], fs::absolute(dir / "cup.yaml").lexically_normal().string());
  EXPECT_NE(touchcloud::test::read_file(dir / "out/report.html").find("<title>touchcloud report: p on my_cup</title>"),
            std::string::npos);

  write_file(dir / "q.yaml", "pipeline: q\n" + body);
  const auto none = run_cli({"validate", (dir / "q.yaml").string()});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("'{scene}' needs the run's scene"), std::string::npos) << none.err;
}

// The last line of a run puts the accuracy (Eq. 11) beside what it hides:
// ground truth 0, 10, 20 mm on x, the estimate 1 mm above 0 and 2 mm above
// 10: est -> gt 1.5 mm, gt -> est (3 + sqrt(104)) / 3 = 4.4 mm, F-score 0.4
// and recall 1/3 at 1.5 mm.
TEST(Cli, TheLastLineOfARunGivesTheAccuracyAndTheCoverage) {
  touchcloud::test::TempDir dir;
  touchcloud::test::save_pcd(dir / "gt.pcd", cloud_of({{0, 0, 0}, {10, 0, 0}, {20, 0, 0}}));
  touchcloud::test::save_pcd(dir / "est.pcd", cloud_of({{0, 0, 1}, {10, 0, 2}}));
  const auto scored = [&](const std::string& metrics) {
    write_file(dir / "p.yaml", "pipeline: p\nstages:\n  - id: read\n    plugin: cloud_reader\n"
                               "    params: {path: est.pcd}\n  - id: score\n    plugin: chamfer\n"
                               "    params: {ground_truth: gt.pcd, metrics: '" + metrics + "'}\n"
                               "    inputs: {cloud: read.cloud}\n");
    const auto r = run_cli({"run", (dir / "p.yaml").string(), "--out", (dir / ("out_" + metrics.substr(0, 3))).string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::string out = r.out.substr(0, r.out.size() - 1);
    return out.substr(out.rfind('\n') + 1);
  };
  EXPECT_EQ(scored("chamfer_est_to_gt, chamfer_gt_to_est, fscore"),
            "headline: score.chamfer_est_to_gt 1.5 mm; completeness 4.39935 mm, F-score 0.4, coverage 0.333333");
  EXPECT_EQ(scored("chamfer_est_to_gt"),
            "headline: score.chamfer_est_to_gt 1.5 mm; coverage not measured (the scoring stage computes no "
            "completeness, F-score or recall: add them to its metrics)");
}

TEST(Cli, UsageErrorsAndMissingFilesExitTwo) {
  auto r = run_cli({"run"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has_line_starting(r.err, "touchcloud: error: ")) << r.err;
  r = run_cli({"frobnicate"});
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli({"validate", "/no/such/pipeline.yaml"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has_line_starting(r.err, "touchcloud: error: /no/such/pipeline.yaml: cannot read the pipeline file"))
      << r.err;
}

TEST(Cli, AStageThatThrowsExitsOneNamingTheStage) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml", "stages:\n  - id: tear\n    plugin: test_throwing\n");
  const auto r = run_cli({"run", (dir / "p.yaml").string(), "--out", (dir / "out").string()}, kTestPlugins);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has_line_starting(r.err, "touchcloud: error: stage 'tear' (plugin test_throwing) failed in process"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Bad data met by a stage while running: a first touch whose 5 points share
// one (x, y) leaves gp_surface no length scale to select. Exit 2, the error
// located at the stage, the last line true though stages ran, and no --out.
TEST(Cli, BadTouchDataFoundByAStageExitsTwoAndWritesNothing) {
  touchcloud::test::TempDir dir;
  touchcloud::PointCloud same;
  for (int k = 1; k <= 5; ++k) same.push_back(pcl::PointXYZ(3, 4, k));
  touchcloud::test::save_pcd(dir / "same_spot.pcd", same);
  write_file(dir / "p.yaml",
             "stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: same_spot.pcd}\n"
             "  - id: fit\n    plugin: gp_surface\n    inputs: {cloud: read.cloud}\n"
             "  - id: sample\n    plugin: surface_sampler\n"
             "    params: {workspace_x_mm: [0, 10], workspace_y_mm: [0, 10], resolution: [5, 5]}\n"
             "    inputs: {surface: fit.surface}\n"
             "  - id: write\n    plugin: cloud_writer\n    params: {path: surface.pcd}\n    inputs: {cloud: sample.cloud}\n");
  const auto r = run_cli({"run", (dir / "p.yaml").string(), "--out", (dir / "out").string(), "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has_line_starting(r.err, (dir / "p.yaml").string() + ":5:9: error: stage 'fit' (plugin gp_surface): "))
      << r.err;
  EXPECT_NE(r.err.find("all 5 training points share (x, y) = (3, 4) mm"), std::string::npos) << r.err;
  ASSERT_FALSE(r.err.empty());
  const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
  EXPECT_EQ(last, "touchcloud: error: 1 problem found; nothing was written\n");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Cli, PluginsListsEveryPluginWithItsParameters) {
  const auto r = run_cli({"plugins"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"cloud_reader - ", "downsample - ", "cloud_writer - ", "leaf_size_mm", "search path:"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
}

TEST(Cli, PluginsNameDescribesOneInFullAndAsJson) {
  auto r = run_cli({"plugins", "downsample"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("inputs:"), std::string::npos);
  EXPECT_NE(r.out.find("> 0"), std::string::npos) << r.out;
  r = run_cli({"plugins", "downsample", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["name"], "downsample");
  bool found = false;
  for (const auto& p : j["parameters"])
    if (p["name"] == "leaf_size_mm") {
      found = true;
      EXPECT_EQ(p["unit"], "mm");
      EXPECT_EQ(p["default"], 1.0);
      EXPECT_EQ(p["min"]["value"], 0.0);
      EXPECT_TRUE(p["min"]["exclusive"].get<bool>());
    }
  EXPECT_TRUE(found);
  r = run_cli({"plugins", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GE(nlohmann::json::parse(r.out).size(), 3u);
}

TEST(Cli, PluginsReportsLoadFailuresAndAbiMismatch) {
  auto r = run_cli({"plugins", "test_old_abi"}, kTestPlugins);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("ABI version 0"), std::string::npos) << r.err;
  r = run_cli({"plugins", "downsampel"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean 'downsample'?"), std::string::npos) << r.err;
}
