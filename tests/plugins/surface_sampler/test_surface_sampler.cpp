// The sampled surface lies on the model's mean, on the requested lattice.
#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"

using namespace touchcloud;

class SurfaceSampler : public touchcloud::test::PipelineFixture {};

TEST_F(SurfaceSampler, LatticeOfTheMeanOverTheWorkspace) {
  Pipeline p = load(
      "stages:\n  - id: model\n    plugin: test_plane_surface\n    params: {slope: [0.5, -0.25], offset_mm: 3}\n"
      "  - id: sample\n    plugin: surface_sampler\n"
      "    params: {workspace_x_mm: [-10, 10], workspace_y_mm: [0, 40], resolution: [21, 5]}\n"
      "    inputs: {surface: model.surface}\n"
      "  - id: write\n    plugin: cloud_writer\n    params: {path: s.pcd}\n    inputs: {cloud: sample.cloud}\n");
  RunOptions o;
  o.quiet = true;
  o.out_dir = dir_ / "out";
  run_pipeline(p, o);
  const PointCloud c = touchcloud::test::load_cloud(dir_ / "out/s.pcd");
  ASSERT_EQ(c.size(), 105u);
  EXPECT_FLOAT_EQ(c[0].x, -10);
  EXPECT_FLOAT_EQ(c[0].y, 0);
  EXPECT_FLOAT_EQ(c[1].x, -9);
  EXPECT_FLOAT_EQ(c[104].y, 40);
  for (const auto& q : c.points) EXPECT_NEAR(q.z, 0.5 * q.x - 0.25 * q.y + 3, 1e-5);
}
