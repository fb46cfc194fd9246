// pipelines/closed_object_fingertip.yaml is closed_object_all_sides.yaml
// with the options its header lists, and nothing else: the same seed gives
// the same surface and mesh, byte for byte, as the latter with each option
// given on the command line (what the docs and the closed-object table
// claim), here in the mug's first four touches with the 20 mm fingertip.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "test_support.hpp"

using touchcloud::test::run_cli;

TEST(ClosedObjectFingertip, IsTheAllSidesPipelineWithItsOptions) {
  touchcloud::test::TempDir dir;
  const auto source = touchcloud::test::source_dir();
  const std::vector<std::string> common = {
      "--scene", (source / "sample_clouds/closed_objects/mug/scene_fingertip.yaml").string(), "--seed", "1",
      "--quiet", "--set", "explore.max_iterations=4"};
  auto run = [&](const std::string& pipeline, const std::string& out, std::vector<std::string> sets) {
    std::vector<std::string> args = {"run", (source / "pipelines" / pipeline).string(), "--out", (dir / out).string()};
    args.insert(args.end(), common.begin(), common.end());
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    const auto r = run_cli(args);
    ASSERT_EQ(r.exit_code, 0) << pipeline << ": " << r.err;
  };
  run("closed_object_fingertip.yaml", "fingertip", {});
  run("closed_object_all_sides.yaml", "all_sides",
      {"plan.oblique_deg=[20,40,60,75]", "plan.table_clearance_mm=10", "fit.surface=local_quadrics",
       "fit.quadric_edge_deg=60", "fit.free_support_mm=3.5", "fit.plan_gaps=true", "fit.swept_mm=40",
       "fit.piece_support_mm=10"});
  for (const char* file : {"mug_surface.pcd", "mug_mesh.ply", "mug_touch_points.pcd"}) {
    const std::string a = touchcloud::test::read_file(dir / "fingertip" / file);
    ASSERT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == touchcloud::test::read_file(dir / "all_sides" / file)) << file << " differs";
  }
  // The pieces far from every touch are counted (the metric is there with the option only).
  const auto summary = nlohmann::json::parse(touchcloud::test::read_file(dir / "fingertip/summary.json"));
  ASSERT_TRUE(summary["metrics"].contains("fit.dropped_unsupported_triangles")) << summary["metrics"].dump();
  EXPECT_GE(summary["metrics"]["fit.dropped_unsupported_triangles"]["value"].get<double>(), 0);
  // Without the swept approaches the surface is another.
  run("closed_object_fingertip.yaml", "unswept", {"fit.swept_mm=0"});
  EXPECT_FALSE(touchcloud::test::read_file(dir / "fingertip/mug_mesh.ply") ==
               touchcloud::test::read_file(dir / "unswept/mug_mesh.ply"));
}
