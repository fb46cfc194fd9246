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

// z = x mm over [0, 100] (a surface swinging far from its data), fitted to
// points with z in [0, 10]; its standard deviation is x / 10 mm.
class SwingingSurface final : public SurfaceModel {
 public:
  std::size_t training_size() const override { return 3; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override { return xy.col(0); }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override { return (xy.col(0) / 10).array().square(); }
  std::optional<std::array<double, 2>> data_z_range_mm() const override { return std::array<double, 2>{0, 10}; }
  std::map<std::string, double> hyperparameters() const override { return {}; }
};

std::map<std::string, ParamValue> swing_params(std::map<std::string, ParamValue> more) {
  more["workspace_x_mm"] = std::vector<double>{0, 100};
  more["workspace_y_mm"] = std::vector<double>{0, 10};
  more["resolution"] = std::vector<std::int64_t>{101, 2};
  return more;
}
}  // namespace

// A mean more than the margin outside the data's z range is extrapolation:
// masked by default (here x > 30 with margin 20), or the run fails, or it is
// kept; each way it is counted, never passed on silently.
TEST(SurfaceSamplerStage, AMeanFarOutsideTheDataIsMaskedOrAnError) {
  const auto model = SurfaceModelPtr(std::make_shared<SwingingSurface>());
  touchcloud::test::StageHarness mask("surface_sampler", swing_params({}));
  mask.configure();
  const CloudConstPtr masked = mask.process_one<CloudConstPtr>({{"surface", model}}, "cloud");
  EXPECT_EQ(masked->size(), 2u * 31u);  // x = 0 .. 30
  for (const auto& q : masked->points) EXPECT_LE(q.z, 30.0f);
  EXPECT_EQ(mask.metric("extrapolated_points"), 2 * 70);

  touchcloud::test::StageHarness keep("surface_sampler", swing_params({{"outside_data", std::string("keep")}}));
  keep.configure();
  EXPECT_EQ(keep.process_one<CloudConstPtr>({{"surface", model}}, "cloud")->size(), 2u * 101u);
  EXPECT_EQ(keep.metric("extrapolated_points"), 2 * 70);

  touchcloud::test::StageHarness error("surface_sampler", swing_params({{"outside_data", std::string("error")}}));
  error.configure();
  try {
    error.process_one<CloudConstPtr>({{"surface", model}}, "cloud");
    FAIL() << "an extrapolated surface passed";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the fitted points' z range [0, 10] mm"), std::string::npos) << e.what();
  }
}

// max_sd_mm drops points where the model is unsure (sd = x / 10 > 2: x > 20).
TEST(SurfaceSamplerStage, MaxSdMasksWhereTheModelIsUnsure) {
  touchcloud::test::StageHarness stage("surface_sampler", swing_params({{"max_sd_mm", 2.0}}));
  stage.configure();
  const CloudConstPtr c =
      stage.process_one<CloudConstPtr>({{"surface", SurfaceModelPtr(std::make_shared<SwingingSurface>())}}, "cloud");
  EXPECT_EQ(c->size(), 2u * 21u);  // x = 0 .. 20
  EXPECT_EQ(stage.metric("uncertain_points"), 2 * 10);  // x = 21 .. 30; beyond, extrapolated first
}

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
