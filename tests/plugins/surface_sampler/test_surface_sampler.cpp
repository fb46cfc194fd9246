// The sampled surface lies on the model's mean, on the requested lattice;
// the same model again gives the same points without evaluating it again; an
// empty workspace is refused at validation.
#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/surface_model.hpp"

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

// As next_touch: an empty workspace along x or y (max not above min) is
// refused when the pipeline is checked, at the parameter's line.
TEST_F(SurfaceSampler, EmptyWorkspaceIsRefusedAtValidation) {
  for (const std::string& bad : {std::string("workspace_x_mm: [10, 10], workspace_y_mm: [0, 10]"),
                                 std::string("workspace_y_mm: [20, 10], workspace_x_mm: [0, 10]")}) {
    const auto d = errors(
        "stages:\n  - id: model\n    plugin: test_plane_surface\n"
        "  - id: sample\n    plugin: surface_sampler\n    params: {" + bad + "}\n"
        "    inputs: {surface: model.surface}\n");
    ASSERT_EQ(d.size(), 1u) << bad;
    const std::string parameter = bad.substr(0, bad.find(':'));
    EXPECT_TRUE(touchcloud::test::mentions(d[0], "parameter '" + parameter + "': the workspace is empty")) << d[0].str();
    EXPECT_EQ(d[0].where.line, 6) << bad;
  }
}

namespace {
// z = height everywhere; counts its lattice evaluations.
class CountingPlane final : public SurfaceModel {
 public:
  explicit CountingPlane(double height_mm) : height_mm_(height_mm) {}
  std::size_t training_size() const override { return 0; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override {
    ++evaluations;
    return Eigen::VectorXd::Constant(xy.rows(), height_mm_);
  }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override { return Eigen::VectorXd::Zero(xy.rows()); }
  std::map<std::string, double> hyperparameters() const override { return {}; }
  mutable int evaluations = 0;

 private:
  double height_mm_;
};
}  // namespace

TEST(SurfaceSamplerStage, TheSameModelAgainGivesTheSamePointsWithoutEvaluating) {
  touchcloud::test::StageHarness stage(
      "surface_sampler", {{"workspace_x_mm", std::vector<double>{0, 10}}, {"workspace_y_mm", std::vector<double>{0, 10}},
                          {"resolution", std::vector<std::int64_t>{11, 11}}});
  stage.configure();
  const auto first = std::make_shared<CountingPlane>(2.0), second = std::make_shared<CountingPlane>(5.0);
  const auto sample = [&](const std::shared_ptr<CountingPlane>& model) {
    return stage.process_one<CloudConstPtr>({{"surface", SurfaceModelPtr(model)}}, "cloud");
  };
  const CloudConstPtr a = sample(first);
  ASSERT_EQ(a->size(), 121u);
  EXPECT_FLOAT_EQ(a->points[60].z, 2.0f);
  EXPECT_EQ(sample(first), a);
  EXPECT_EQ(first->evaluations, 1);
  const CloudConstPtr b = sample(second);
  EXPECT_NE(b, a);
  EXPECT_FLOAT_EQ(b->points[60].z, 5.0f);
  EXPECT_EQ(second->evaluations, 1);
}
