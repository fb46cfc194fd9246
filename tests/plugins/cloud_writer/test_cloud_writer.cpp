// cloud_writer: what it writes reads back identically, in both formats.
#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

class CloudWriter : public touchcloud::test::PipelineFixture {};

TEST_F(CloudWriter, RoundTripsThroughPcdAndPly) {
  const PointCloud grid = touchcloud::test::grid_cloud(5, 1.25);
  touchcloud::test::save_pcd(dir_ / "in.pcd", grid);
  for (const std::string out : {"copy.pcd", "copy.ply", "nested/ascii.ply"}) {
    Pipeline p = load("stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: in.pcd}\n"
                      "  - id: write\n    plugin: cloud_writer\n    params: {path: " + out +
                      ", binary: " + (out.find("ascii") == std::string::npos ? "true" : "false") +
                      "}\n    inputs: {cloud: read.cloud}\n");
    RunOptions o;
    o.quiet = true;
    o.out_dir = dir_ / "out";
    const RunResult r = run_pipeline(p, o);
    ASSERT_EQ(r.record.outputs, std::vector<std::string>{out});
    const PointCloud back = touchcloud::test::load_cloud(dir_ / "out" / out);
    ASSERT_EQ(back.size(), grid.size()) << out;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      EXPECT_EQ(back[i].x, grid[i].x);
      EXPECT_EQ(back[i].y, grid[i].y);
      EXPECT_EQ(back[i].z, grid[i].z);
    }
  }
}

TEST_F(CloudWriter, IterationPlaceholderNamesOneFilePerIteration) {
  touchcloud::test::save_pcd(dir_ / "in.pcd", touchcloud::test::grid_cloud(2, 1.0));
  Pipeline p = load("stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: in.pcd}\n"
                    "  - id: l\n    loop:\n      max_iterations: 3\n      stages:\n"
                    "        - id: write\n          plugin: cloud_writer\n"
                    "          params: {path: 'touch_{iteration}.pcd'}\n          inputs: {cloud: read.cloud}\n");
  RunOptions o;
  o.quiet = true;
  o.out_dir = dir_ / "out";
  run_pipeline(p, o);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::filesystem::exists(dir_ / "out" / ("touch_" + std::to_string(i) + ".pcd")));
}

TEST_F(CloudWriter, RefusesUnknownFormatsAndPathsOutsideTheOutputFolder) {
  touchcloud::test::save_pcd(dir_ / "in.pcd", touchcloud::test::grid_cloud(2, 1.0));
  const std::string head = "stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: in.pcd}\n"
                           "  - id: write\n    plugin: cloud_writer\n    inputs: {cloud: read.cloud}\n";
  const auto d = errors(head + "    params: {path: out.xyz}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "unsupported extension '.xyz'")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 8);

  // Refused when the pipeline loads (so `validate` refuses it too), at the value.
  const auto escape = errors(head + "    params: {path: ../escape.pcd}\n");
  ASSERT_EQ(escape.size(), 1u);
  EXPECT_TRUE(mentions(escape[0], "output file '../escape.pcd' must stay inside the output folder")) << escape[0].str();
  EXPECT_EQ(escape[0].where.line, 8);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "escape.pcd"));
}
