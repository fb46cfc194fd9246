// touchcloud score, run as a user runs it: hand-checked values, tables and
// JSON, batches that survive a bad estimate, folders, globs, manifests, mesh
// ground truth, and the exit statuses of the CLI contract.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "cloud_files.hpp"
#include "test_support.hpp"

using touchcloud::PointCloud;
using touchcloud::test::run_cli;
using touchcloud::test::save_pcd;
using touchcloud::test::TempDir;
using touchcloud::test::write_file;
using nlohmann::json;

namespace {

PointCloud cloud(std::initializer_list<std::array<float, 3>> points) {
  PointCloud c;
  for (const auto& p : points) c.push_back(pcl::PointXYZ(p[0], p[1], p[2]));
  return c;
}

// Ground truth: three points 10 mm apart on the x axis. Estimate: 1 mm above
// the first and 2 mm above the second. By hand: est -> gt 1.5 mm; gt -> est
// (1 + 2 + sqrt(104)) / 3; Hausdorff sqrt(104); at 1.5 mm precision 1/2,
// recall 1/3, F-score 0.4.
const PointCloud kGroundTruth = cloud({{0, 0, 0}, {10, 0, 0}, {20, 0, 0}});
const PointCloud kEstimate = cloud({{0, 0, 1}, {10, 0, 2}});

// save_pcd into a folder that may not exist yet.
void save(const std::filesystem::path& file, const PointCloud& c) {
  std::filesystem::create_directories(file.parent_path());
  save_pcd(file, c);
}

int count_lines_starting(const std::string& text, const std::string& prefix) {
  int n = 0;
  std::size_t at = 0;
  while (at < text.size()) {
    if (text.compare(at, prefix.size(), prefix) == 0) ++n;
    at = text.find('\n', at);
    if (at == std::string::npos) break;
    ++at;
  }
  return n;
}

}  // namespace

class ScoreVerb : public ::testing::Test {
 protected:
  void SetUp() override {
    save_pcd(dir_ / "gt.pcd", kGroundTruth);
    save_pcd(dir_ / "est.pcd", kEstimate);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  TempDir dir_;
};

TEST_F(ScoreVerb, HandCheckedCloudsAsJson) {
  const auto r = run_cli({"score", "--gt", path("gt.pcd"), path("est.pcd"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "") << "no progress or noise on stderr when it is not a terminal";
  const json all = json::parse(r.out);
  ASSERT_EQ(all.size(), 1u);
  const json& rec = all[0];
  EXPECT_EQ(rec["status"], "ok");
  EXPECT_EQ(rec["estimate"], path("est.pcd"));
  EXPECT_EQ(rec["estimate_points"], 2);
  EXPECT_EQ(rec["ground_truth"]["kind"], "cloud");
  EXPECT_EQ(rec["ground_truth"]["points"], 3);
  const json& m = rec["metrics"];
  EXPECT_DOUBLE_EQ(m["chamfer_est_to_gt_mm"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(m["chamfer_gt_to_est_mm"].get<double>(), (3 + std::sqrt(104.0)) / 3);
  EXPECT_DOUBLE_EQ(m["chamfer_symmetric_mm"].get<double>(), 0.5 * (1.5 + (3 + std::sqrt(104.0)) / 3));
  EXPECT_DOUBLE_EQ(m["hausdorff_mm"].get<double>(), std::sqrt(104.0));
  EXPECT_DOUBLE_EQ(m["fscore"].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(m["precision"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(m["recall"].get<double>(), 1.0 / 3);
  EXPECT_FALSE(m.contains("fscore_threshold_mm")) << "a setting, not a metric";
  EXPECT_DOUBLE_EQ(rec["fscore_threshold_mm"].get<double>(), 1.5);
}

TEST_F(ScoreVerb, TableShowsMetricsInMillimetres) {
  const auto r = run_cli({"score", "--gt", path("gt.pcd"), path("est.pcd"), "--fscore-threshold", "2.5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("est->gt mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("hausdorff mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("F@2.50mm"), std::string::npos) << r.out;
  // est -> gt 1.5; gt -> est 13.198 / 3 = 4.399; symmetric 2.950; Hausdorff
  // 10.198; at
  // 2.5 mm both estimated points match (P = 1) and two of three gt points
  // (R = 2/3): F = 0.8.
  const std::string row = r.out.substr(r.out.find(path("est.pcd")));
  for (const char* v : {" 1.500 ", " 4.399 ", " 2.950 ", " 10.198 ", " 0.800 ", " 1.000 ", " 0.667"})
    EXPECT_NE(row.find(v), std::string::npos) << v << " in\n" << r.out;
}

TEST_F(ScoreVerb, MetricsOptionSelectsWhatIsComputed) {
  // Before the estimates: --metrics takes one list, not the estimates too.
  const auto r = run_cli({"score", "--metrics", "chamfer_est_to_gt", "--gt", path("gt.pcd"), path("est.pcd"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json m = json::parse(r.out)[0]["metrics"];
  ASSERT_EQ(m.size(), 1u) << m.dump();
  EXPECT_DOUBLE_EQ(m["chamfer_est_to_gt_mm"].get<double>(), 1.5);
}

TEST_F(ScoreVerb, OneBadEstimateDoesNotStopTheBatch) {
  write_file(dir_ / "empty.pcd", "");
  save_pcd(dir_ / "far.pcd", cloud({{0, 0, 4}}));
  const auto r = run_cli({"score", "--gt", path("gt.pcd"), path("est.pcd"), path("empty.pcd"), path("missing.pcd"),
                          path("far.pcd"), "--json"});
  EXPECT_EQ(r.exit_code, 2) << "some estimates were bad input";
  const json all = json::parse(r.out);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0]["status"], "ok");
  EXPECT_EQ(all[1]["status"], "error");
  EXPECT_NE(all[1]["error"].get<std::string>().find("empty.pcd"), std::string::npos);
  EXPECT_EQ(all[2]["status"], "error");
  EXPECT_NE(all[2]["error"].get<std::string>().find("missing.pcd"), std::string::npos);
  EXPECT_EQ(all[3]["status"], "ok");
  EXPECT_DOUBLE_EQ(all[3]["metrics"]["chamfer_est_to_gt_mm"].get<double>(), 4.0);
  EXPECT_EQ(count_lines_starting(r.err, "touchcloud: error:"), 3) << r.err;
  EXPECT_NE(r.err.find("2 of 4 estimates could not be scored"), std::string::npos) << r.err;

  const auto table = run_cli({"score", "--gt", path("gt.pcd"), path("est.pcd"), path("empty.pcd")});
  EXPECT_EQ(table.exit_code, 2);
  EXPECT_NE(table.out.find("error: " + path("empty.pcd") + " is empty"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find(" 1.500 "), std::string::npos) << table.out;
}

TEST_F(ScoreVerb, FoldersAndGlobsExpandToTheCloudsInThem) {
  save(dir_ / "runs/a.pcd", kEstimate);
  save(dir_ / "runs/deeper/b.pcd", cloud({{0, 0, 3}}));
  save(dir_ / "runs/.touchcloud-staging-1/c.pcd", kEstimate);  // hidden: skipped
  write_file(dir_ / "runs/summary.json", "{}");                      // not a cloud: skipped
  const auto folder = run_cli({"score", "--gt", path("gt.pcd"), path("runs"), "--json"});
  ASSERT_EQ(folder.exit_code, 0) << folder.err;
  const json f = json::parse(folder.out);
  ASSERT_EQ(f.size(), 2u) << f.dump(1);
  EXPECT_EQ(f[0]["estimate"], path("runs/a.pcd"));
  EXPECT_EQ(f[1]["estimate"], path("runs/deeper/b.pcd"));
  EXPECT_DOUBLE_EQ(f[1]["metrics"]["chamfer_est_to_gt_mm"].get<double>(), 3.0);

  // The glob reaches the CLI unexpanded (run_cli quotes it), as from a script.
  const auto glob = run_cli({"score", "--gt", path("gt.pcd"), path("runs/*/*.pcd"), path("nothing*.pcd"), "--json"});
  EXPECT_EQ(glob.exit_code, 2);
  const json g = json::parse(glob.out);
  ASSERT_EQ(g.size(), 2u) << g.dump(1);
  EXPECT_EQ(g[0]["estimate"], path("runs/deeper/b.pcd"));
  EXPECT_EQ(g[1]["status"], "error");
  EXPECT_NE(g[1]["error"].get<std::string>().find("no file matches"), std::string::npos);
}

TEST_F(ScoreVerb, ScoresTheOutputFolderOfARun) {
  const std::string demo = (touchcloud::test::source_dir() / "pipelines/downsample_cloud.yaml").string();
  ASSERT_EQ(run_cli({"run", demo, "--out", path("out"), "--quiet"}).exit_code, 0);
  const std::string gt = touchcloud::test::gel_dome_cloud();
  const auto r = run_cli({"score", "--gt", gt, path("out"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json all = json::parse(r.out);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0]["estimate"], path("out/gel_dome_thinned.ply"));
  // Voxel centroids of a 4 mm grid lie within a voxel diagonal of the cloud.
  const double d = all[0]["metrics"]["chamfer_est_to_gt_mm"].get<double>();
  EXPECT_GT(d, 0.0);
  EXPECT_LT(d, 4.0 * std::sqrt(3.0));
}

TEST_F(ScoreVerb, ManifestPairsEstimatesWithTheirOwnGroundTruth) {
  save(dir_ / "batch/gt_up.pcd", cloud({{0, 0, 5}, {10, 0, 5}, {20, 0, 5}}));
  save(dir_ / "batch/est_a.pcd", kEstimate);
  write_file(dir_ / "batch/list.csv",
             "estimate,ground_truth\n"
             "# paths are relative to this file\n"
             "est_a.pcd, gt_up.pcd\n"
             "\"../est.pcd\",\n"
             "est_a.pcd,../gt.pcd\n");
  const auto r = run_cli({"score", "--gt", path("gt.pcd"), path("batch/list.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json all = json::parse(r.out);
  ASSERT_EQ(all.size(), 3u);
  // Against ground truth 5 mm up, the estimate is 4 and 3 mm away: 3.5.
  EXPECT_EQ(all[0]["ground_truth"]["file"], path("batch/gt_up.pcd"));
  EXPECT_DOUBLE_EQ(all[0]["metrics"]["chamfer_est_to_gt_mm"].get<double>(), 3.5);
  EXPECT_EQ(all[1]["ground_truth"]["file"], path("gt.pcd"));  // from --gt
  EXPECT_DOUBLE_EQ(all[1]["metrics"]["chamfer_est_to_gt_mm"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(all[2]["metrics"]["chamfer_est_to_gt_mm"].get<double>(), 1.5);

  const auto table = run_cli({"score", "--gt", path("gt.pcd"), path("batch/list.csv")});
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("ground truth "), std::string::npos) << "a column when pairs differ:\n" << table.out;

  // A row whose own ground truth is unreadable fails alone.
  write_file(dir_ / "batch/broken.csv", "est_a.pcd,missing_gt.stl\nest_a.pcd,gt_up.pcd\n");
  const auto broken = run_cli({"score", path("batch/broken.csv"), "--json"});
  EXPECT_EQ(broken.exit_code, 2);
  const json b = json::parse(broken.out);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0]["status"], "error");
  EXPECT_NE(b[0]["error"].get<std::string>().find("missing_gt.stl"), std::string::npos) << b[0].dump();
  EXPECT_DOUBLE_EQ(b[1]["metrics"]["chamfer_est_to_gt_mm"].get<double>(), 3.5);
}

TEST_F(ScoreVerb, ManifestErrorsNameTheLine) {
  write_file(dir_ / "bad.csv", "estimate,ground_truth\nest.pcd,gt.pcd,extra\n");
  const auto r = run_cli({"score", path("bad.csv")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(path("bad.csv") + ":2:1: error:"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");

  write_file(dir_ / "no_gt.csv", "est.pcd\n");
  const auto no_gt = run_cli({"score", path("no_gt.csv")});
  EXPECT_EQ(no_gt.exit_code, 2);
  EXPECT_NE(no_gt.err.find("no ground truth for est.pcd"), std::string::npos) << no_gt.err;
}

TEST_F(ScoreVerb, BadGroundTruthOrUsageStopsWithOneErrorLine) {
  write_file(dir_ / "garbage.stl", "not a mesh\n");
  const std::vector<std::vector<std::string>> cases = {
      {"score", "--gt", path("garbage.stl"), path("est.pcd")},
      {"score", "--gt", path("missing.pcd"), path("est.pcd")},
      {"score", path("est.pcd")},
      {"score", "--gt", path("gt.pcd"), path("est.pcd"), "--metrics", "chamfer,hausdorff"},
      {"score", "--gt", path("gt.pcd"), path("est.pcd"), "--fscore-threshold", "0"},
      {"score", "--gt", path("gt.pcd"), path("est.pcd"), "--fscore-threshold", "nan"},
      {"score", "--gt", path("gt.pcd"), path("est.pcd"), "--fscore-threshold", "inf"},
      {"score", "--gt", path("gt.pcd")},
  };
  for (const auto& args : cases) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args.back();
    EXPECT_EQ(count_lines_starting(r.err, "touchcloud: error:"), 1) << r.err;
    EXPECT_EQ(r.out, "") << "nothing scored";
  }
  EXPECT_NE(run_cli(cases[0]).err.find("garbage.stl"), std::string::npos);
  EXPECT_NE(run_cli(cases[3]).err.find("unknown metric 'chamfer'"), std::string::npos);
}

TEST_F(ScoreVerb, MeshGroundTruthIsSampledReproducibly) {
  write_file(dir_ / "square.obj", "v 0 0 0\nv 100 0 0\nv 100 100 0\nv 0 100 0\nf 1 2 3 4\n");
  save_pcd(dir_ / "above.pcd", cloud({{50, 50, 2}, {20, 30, 2}, {70, 10, 2}}));
  const auto metrics = [&](const std::string& seed) {
    const auto r = run_cli({"score", "--gt", path("square.obj"), path("above.pcd"), "--json", "--samples", "40000",
                            "--seed", seed, "--metrics", "chamfer_est_to_gt"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const json rec = json::parse(r.out)[0];
    EXPECT_EQ(rec["ground_truth"]["kind"], "mesh");
    EXPECT_EQ(rec["ground_truth"]["points"], 40000);
    EXPECT_DOUBLE_EQ(rec["ground_truth"]["area_mm2"].get<double>(), 10000.0);
    EXPECT_DOUBLE_EQ(rec["ground_truth"]["sample_spacing_mm"].get<double>(), 0.5);
    return rec["metrics"]["chamfer_est_to_gt_mm"].get<double>();
  };
  const double a = metrics("3"), b = metrics("3"), c = metrics("4");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // 2 mm above a plane sampled 4 per mm^2: 2 + about 1 / (2 pi 4 2) = 0.02 mm.
  EXPECT_GT(a, 2.0);
  EXPECT_LT(a, 2.1);
}

// A scene is ground truth as simulated (a 20 mm cube at scale 2 is 40 mm);
// from_above keeps its top, which the estimate (the top, 1 mm apart) covers,
// and leaves out the walls and bottom that no press from above reaches.
TEST_F(ScoreVerb, ASceneIsGroundTruthAndFromAboveScoresWhatAPressCanSee) {
  write_file(dir_ / "cube.obj", touchcloud::test::cube_obj(20));
  write_file(dir_ / "scene.yaml", "object: {mesh: cube.obj, scale: 2}\n");
  save_pcd(dir_ / "top.pcd", touchcloud::test::cube_top(40, 41));
  const auto score = [&](const std::string& visible) {
    const auto r = run_cli({"score", "--gt", path("scene.yaml"), path("top.pcd"), "--json", "--samples", "96000",
                            "--visible", visible});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out)[0];
  };
  const json all = score("all"), above = score("from_above");
  EXPECT_EQ(all["ground_truth"]["visible"], "all");
  EXPECT_DOUBLE_EQ(all["ground_truth"]["area_mm2"].get<double>(), 9600.0);
  // On the surface, 10 samples per mm^2 leave 1 / (2 sqrt(10)) = 0.16 mm (docs/scoring.md).
  EXPECT_LT(all["metrics"]["chamfer_est_to_gt_mm"].get<double>(), 0.2);
  EXPECT_LT(all["metrics"]["recall"].get<double>(), 0.3);  // the top and a band of the walls: ~0.22
  // Scored whole, the share of what a press from above sees stands beside it.
  EXPECT_NEAR(all["ground_truth"]["seen_from_above_points"].get<double>() / 96000, 1.0 / 6, 0.01);
  EXPECT_GT(all["metrics"]["visible_recall"].get<double>(), 0.99);
  EXPECT_FALSE(above["metrics"].contains("visible_recall"));  // there recall is that share
  EXPECT_EQ(above["ground_truth"]["visible"], "from_above");
  EXPECT_NEAR(above["ground_truth"]["hidden_points"].get<double>() / 96000, 5.0 / 6, 0.01);
  EXPECT_GT(above["metrics"]["recall"].get<double>(), 0.99);
  EXPECT_LT(above["metrics"]["chamfer_gt_to_est_mm"].get<double>(), 0.5);
  const auto table = run_cli({"score", "--gt", path("scene.yaml"), path("top.pcd"), "--samples", "96000",
                              "--visible", "from_above"});
  EXPECT_NE(table.out.find("visible from above only"), std::string::npos) << table.out;
  const auto whole = run_cli({"score", "--gt", path("scene.yaml"), path("top.pcd"), "--samples", "96000"});
  EXPECT_NE(whole.out.find("samples seen from above: visible recall"), std::string::npos) << whole.out;
  EXPECT_NE(whole.out.find("visible rec"), std::string::npos) << whole.out;
  EXPECT_EQ(run_cli({"score", "--gt", path("gt.pcd"), path("est.pcd"), "--visible", "from_above"}).exit_code, 2);
}

// A mesh in metres would score as a speck, every distance the object's size.
TEST_F(ScoreVerb, AMeshWhoseSizeSuggestsAnotherUnitIsRefused) {
  write_file(dir_ / "metres.obj", touchcloud::test::cube_obj(0.02));
  const auto r = run_cli({"score", "--gt", path("metres.obj"), path("est.pcd")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the object is only 0.02 mm across: is the mesh in metres or centimetres?"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("touchcloud-make-scene"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(ScoreVerb, HelpStatesTheExitStatuses) {
  const auto r = run_cli({"score", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Exit status"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 bad input"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--metrics"), std::string::npos) << r.out;
}
