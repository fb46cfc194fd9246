// The main job on the shipped closed shapes (sample_clouds/closed_objects),
// run as a user runs it on their own object: `--scene` only. The headline
// shows what was missed (the sides and bottom no press from above reaches)
// and how much of what such a press can see was covered; the planner touches
// no cell the gel cannot reach, and on the small sphere it stops once no
// cell is left instead of spending the rest of the budget.
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace fs = std::filesystem;
using touchcloud::test::run_cli;

namespace {
struct ObjectRun {
  nlohmann::json summary;
  std::string headline;
};

ObjectRun run_on(const std::string& object, const std::vector<std::string>& more, const fs::path& out) {
  std::vector<std::string> args = {"run", (touchcloud::test::source_dir() / "pipelines/fox_mask_active.yaml").string(),
                                   "--scene",
                                   (touchcloud::test::source_dir() / "sample_clouds/closed_objects" / object /
                                    "scene.yaml").string(),
                                   "--seed", "1", "--quiet", "--out", out.string()};
  args.insert(args.end(), more.begin(), more.end());
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ObjectRun run{nlohmann::json::parse(touchcloud::test::read_file(out / "summary.json")), ""};
  const std::string text = r.out.substr(0, r.out.find_last_not_of('\n') + 1);
  run.headline = text.substr(text.rfind('\n') + 1);
  return run;
}
double metric(const ObjectRun& r, const std::string& key) { return r.summary["metrics"][key]["value"].get<double>(); }
}  // namespace

TEST(ClosedObjects, TheSphereStopsWhenNoCellIsLeftAndItsHeadlineShowsHalfTheObjectMissed) {
  touchcloud::test::TempDir dir;
  const ObjectRun r = run_on("sphere", {}, dir / "sphere");
  // 4 of the 4 x 4 cells lie off the ball, where the gel rests on it far above the table.
  EXPECT_EQ(metric(r, "plan.unreachable_cells"), 4);
  EXPECT_EQ(r.summary["loops"]["explore"]["iterations"], 12);
  EXPECT_EQ(r.summary["loops"]["explore"]["max_iterations"], 34);
  EXPECT_TRUE(r.summary["notes"].contains("plan.stopped"));
  // No touch stopped short of the surface: the simulator's own measure.
  EXPECT_EQ(metric(r, "sensor.unreachable_touches"), 0);
  for (const auto& gap : r.summary["metrics"]["sensor.apex_above_target_mm"]["series"]) EXPECT_LE(gap.get<double>(), 15.0);
  // The bottom half of a ball is out of reach: coverage under 0.6, however good Eq. 11 is.
  EXPECT_LT(metric(r, "score.recall"), 0.6);
  EXPECT_LT(metric(r, "score.chamfer_est_to_gt"), 1.0);
  EXPECT_GT(metric(r, "score.chamfer_gt_to_est"), 3.0);
  EXPECT_EQ(r.headline.rfind("headline: score.chamfer_est_to_gt ", 0), 0u) << r.headline;
  EXPECT_NE(r.headline.find("coverage 0.4"), std::string::npos) << r.headline;
  // Of what a press from above can see, the run covers most: both shares are in the headline.
  EXPECT_GT(metric(r, "score.visible_recall"), 0.85);
  EXPECT_NE(r.headline.find(" (recall), 0.9"), std::string::npos) << r.headline;
  EXPECT_NE(r.headline.find(" (visible_recall)"), std::string::npos) << r.headline;
  EXPECT_TRUE(fs::exists(dir / "sphere/sphere_surface.pcd"));
  EXPECT_EQ(r.summary["scene"]["name"], "sphere");
  // The report heads with both coverages.
  const auto report = run_cli({"report", (dir / "sphere").string(), "--out", (dir / "report.html").string()});
  ASSERT_EQ(report.exit_code, 0) << report.err;
  const std::string page = touchcloud::test::read_file(dir / "report.html");
  EXPECT_NE(page.find(R"({"metric":"score.recall","role":"coverage")"), std::string::npos);
  EXPECT_NE(page.find(R"({"metric":"score.visible_recall","role":"coverage")"), std::string::npos);
}

TEST(ClosedObjects, TheTorusHoleIsLeftOutAndTheMaskedSurfaceIsCountedAsLost) {
  touchcloud::test::TempDir dir;
  const ObjectRun r = run_on("torus", {"--set", "explore.max_iterations=8"}, dir / "torus");
  EXPECT_EQ(metric(r, "plan.unreachable_cells"), 56);
  EXPECT_EQ(metric(r, "sensor.unreachable_touches"), 0);
  EXPECT_EQ(metric(r, "plan.touches_planned"), 8);
  EXPECT_LT(metric(r, "score.recall"), 0.6);
  EXPECT_GT(metric(r, "score.visible_recall"), metric(r, "score.recall"));
  EXPECT_GT(metric(r, "surface.masked_points"), 0);
  EXPECT_NE(r.headline.find("(surface lost to a mask)"), std::string::npos) << r.headline;
}

// The shipped shapes are what a scorer and a simulator can trust: closed
// (every edge shared by two triangles that run it in opposite directions),
// facing outwards (positive enclosed volume, as the generator states it),
// and each says its licence in the mesh file.
TEST(ClosedObjects, EveryShippedShapeIsClosedFacesOutwardsAndStatesItsLicence) {
  const std::map<std::string, double> volume_mm3 = {
      {"torus", 2 * M_PI * M_PI * 40 * 15 * 15}, {"sphere", 4.0 / 3 * M_PI * 15 * 15 * 15},
      {"mug", M_PI * (40 * 40 * 90 - 36 * 36 * 84) + M_PI * M_PI * 24 * 5 * 5},  // cup and half a torus
      {"pebble", 0}, {"step", 50 * 50 * 40 + 40 * 50 * 20}};
  for (const auto& [name, expected] : volume_mm3) {
    SCOPED_TRACE(name);
    const fs::path file = touchcloud::test::source_dir() / "sample_clouds/closed_objects" / name / (name + ".ply");
    const touchcloud::scoring::TriangleMesh mesh = touchcloud::scoring::read_triangle_mesh(file);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    double volume = 0;
    for (const auto& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
      volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6;
    }
    for (const auto& [edge, count] : edges) {
      ASSERT_EQ(count, 1) << edge.first << "-" << edge.second;
      ASSERT_EQ(edges.count({edge.second, edge.first}), 1u) << "open edge " << edge.first << "-" << edge.second;
    }
    if (expected > 0)
      EXPECT_NEAR(volume, expected, 0.02 * expected);  // polygons inside the true curves
    else
      EXPECT_GT(volume, 0);
    std::ifstream in(file);
    std::string header((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(header.substr(0, 300).find("(CC0, made by make_closed_objects.py)"), std::string::npos);
    EXPECT_TRUE(fs::exists(file.parent_path() / "scene.yaml"));
  }
}
