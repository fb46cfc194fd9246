// side_touch in pipelines/closed_object_all_sides.yaml on the shipped torus
// (bottom on the table, 30 mm tall): touches from any side, each checked
// against the scene's object before it is made.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace fs = std::filesystem;
using touchcloud::test::run_cli;

namespace {

nlohmann::json run_torus(const fs::path& out, const std::vector<std::string>& sets) {
  std::vector<std::string> args{"run",
                                (touchcloud::test::source_dir() / "pipelines/closed_object_all_sides.yaml").string(),
                                "--scene",
                                (touchcloud::test::source_dir() / "sample_clouds/closed_objects/torus/scene.yaml").string(),
                                "--seed", "1", "--quiet", "--out", out.string()};
  for (const auto& s : sets) args.insert(args.end(), {"--set", s});
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(touchcloud::test::read_file(out / "summary.json"));
}
double metric(const nlohmann::json& s, const std::string& key) { return s["metrics"][key]["value"].get<double>(); }

}  // namespace

// A start tilted to the horizontal: the 65 mm dome beside a 30 mm tall torus
// would sweep below the table, so all four side approaches are refused for
// the table before they are made, counted, and the touches go elsewhere.
TEST(SideTouch, ApproachesThatWouldMeetTheTableAreRefusedAndCounted) {
  touchcloud::test::TempDir dir;
  const nlohmann::json s = run_torus(dir / "flat", {"explore.max_iterations=3", "plan.start_tilt_deg=90"});
  EXPECT_EQ(metric(s, "plan.touches_planned"), 3);
  EXPECT_GE(metric(s, "plan.refused_table"), 4);
  EXPECT_EQ(metric(s, "plan.refused_touches"), metric(s, "plan.refused_table") + metric(s, "plan.refused_object") +
                                                   metric(s, "plan.refused_workspace") +
                                                   metric(s, "plan.refused_nothing"));
  EXPECT_EQ(metric(s, "sensor.touches"), 3);
}

// The shipped start: straight down, then four approaches 45 degrees from the
// vertical; the fit closes round touches from several sides.
TEST(SideTouch, TheStartTouchesFromSeveralSides) {
  touchcloud::test::TempDir dir;
  const nlohmann::json s = run_torus(dir / "start", {"explore.max_iterations=6"});
  EXPECT_EQ(metric(s, "plan.touches_planned"), 6);
  EXPECT_EQ(metric(s, "sensor.touches"), 6);
  EXPECT_LT(metric(s, "score.chamfer_est_to_gt"), 5.0);
  EXPECT_TRUE(fs::exists(dir / "start/torus_mesh.ply"));
}
