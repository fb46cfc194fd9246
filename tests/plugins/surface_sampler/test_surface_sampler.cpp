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

// The same swing fitted to points with z in [0, 50]: extrapolation only
// beyond x = 70.
class WiderSwing final : public SurfaceModel {
 public:
  std::size_t training_size() const override { return 3; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override { return xy.col(0); }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override { return Eigen::VectorXd::Zero(xy.rows()); }
  std::optional<std::array<double, 2>> data_z_range_mm() const override { return std::array<double, 2>{0, 50}; }
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

// What a mask drops is counted as lost surface (a role the run's headline
// reads), every call, and the run's notes give the last call's counts, not
// the first warning's: 140 points dropped at the first touch, 60 at the last.
TEST(SurfaceSamplerStage, MaskedPointsAreCountedAndTheNotesGiveTheLastCounts) {
  touchcloud::test::StageHarness stage("surface_sampler", swing_params({}));
  stage.configure();
  stage.process_one<CloudConstPtr>({{"surface", SurfaceModelPtr(std::make_shared<SwingingSurface>())}}, "cloud");
  EXPECT_EQ(stage.metric("masked_points"), 2 * 70);
  const CloudConstPtr last =
      stage.process_one<CloudConstPtr>({{"surface", SurfaceModelPtr(std::make_shared<WiderSwing>())}}, "cloud");
  EXPECT_EQ(last->size(), 2u * 71u);
  EXPECT_EQ(stage.metric("masked_points"), 2 * 30);
  stage.finish();
  EXPECT_EQ(stage.metric("lattice_points"), 202);
  const auto& notes = stage.record().notes;
  ASSERT_TRUE(notes.count("stage.extrapolation"));
  EXPECT_NE(notes.at("stage.extrapolation").find("at the last call 60 lattice points"), std::string::npos)
      << notes.at("stage.extrapolation");
  ASSERT_TRUE(notes.count("stage.masked"));
  EXPECT_NE(notes.at("stage.masked").find("60 of 202 lattice points were dropped"), std::string::npos)
      << notes.at("stage.masked");
  const auto& declared = stage.record().metrics.at("stage.masked_points").spec;
  EXPECT_EQ(declared.role, MetricRole::masked_points);
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

namespace {
// z = 0 but for a spike of 8 mm over 4.5 <= x <= 5.5 (the nodes x = 5), the
// way a GP with next to no noise swung between two close touches' points.
class SpikedSurface final : public SurfaceModel {
 public:
  std::size_t training_size() const override { return 11; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override {
    return (xy.col(0).array() - 5.0).abs().unaryExpr([](double d) { return d <= 0.5 ? 8.0 : 0.0; });
  }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override { return Eigen::VectorXd::Zero(xy.rows()); }
  // Inside the data's z range overall: the global check cannot see the spike.
  std::optional<std::array<double, 2>> data_z_range_mm() const override { return std::array<double, 2>{0, 10}; }
  std::map<std::string, double> hyperparameters() const override { return {}; }
};

// Fitted points at z = 0 along y = 1 for x in [x0, x1] mm, 1 mm apart.
CloudConstPtr flat_points(double x0, double x1) {
  auto c = std::make_shared<PointCloud>();
  for (double x = x0; x <= x1; x += 1) c->push_back(pcl::PointXYZ(static_cast<float>(x), 1.0f, 0.0f));
  return c;
}

std::map<std::string, ParamValue> spike_params(std::map<std::string, ParamValue> more) {
  more["workspace_x_mm"] = std::vector<double>{0, 10};
  more["workspace_y_mm"] = std::vector<double>{0, 2};
  more["resolution"] = std::vector<std::int64_t>{11, 3};
  return more;
}

CloudConstPtr sample_spike(touchcloud::test::StageHarness& stage, const CloudConstPtr& points) {
  stage.configure();
  return stage.process_one<CloudConstPtr>(
      {{"surface", SurfaceModelPtr(std::make_shared<SpikedSurface>())}, {"points", points}}, "cloud");
}
}  // namespace

// Given the fitted points, a mean more than near_data_margin_mm off every
// point within near_data_radius_mm of it is counted and warned of (kept by
// default), dropped, or fails the run; the global z range lets it through.
TEST(SurfaceSamplerStage, AMeanSwingingOffTheDataBesideItIsCountedMaskedOrAnError) {
  const CloudConstPtr points = flat_points(0, 10);
  touchcloud::test::StageHarness keep("surface_sampler", spike_params({}));
  EXPECT_EQ(sample_spike(keep, points)->size(), 33u);
  EXPECT_EQ(keep.metric("off_data_points"), 3);  // x = 5 on the three rows
  EXPECT_EQ(keep.metric("extrapolated_points"), 0);
  ASSERT_EQ(keep.record().notes.count("stage.off_data"), 1u);
  EXPECT_NE(keep.record().notes.at("stage.off_data").find("up to 8 mm (z = 8 mm at (5, 0) mm)"), std::string::npos)
      << keep.record().notes.at("stage.off_data");

  touchcloud::test::StageHarness mask("surface_sampler", spike_params({{"near_data", std::string("mask")}}));
  const CloudConstPtr masked = sample_spike(mask, points);
  EXPECT_EQ(masked->size(), 30u);
  for (const auto& q : masked->points) EXPECT_EQ(q.z, 0.0f);

  touchcloud::test::StageHarness error("surface_sampler", spike_params({{"near_data", std::string("error")}}));
  try {
    sample_spike(error, points);
    FAIL() << "a surface swinging off its data passed";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("at (5, 0) mm is z = 8 mm, more than near_data_margin_mm 5 outside the z "
                                         "range [0, 0] mm of the fitted points within 2 mm of it"),
              std::string::npos)
        << e.what();
  }
}

// Where no fitted point lies within the radius the check has nothing to
// hold the mean against (the global range still applies); a wider margin
// lets the spike pass; with no points wired there is no check.
TEST(SurfaceSamplerStage, TheNearDataCheckNeedsNeighboursAndAMeanBeyondTheMargin) {
  touchcloud::test::StageHarness far("surface_sampler", spike_params({{"near_data", std::string("error")}}));
  EXPECT_EQ(sample_spike(far, flat_points(0, 2))->size(), 33u);  // the nearest point to x = 5: 3 mm off
  EXPECT_EQ(far.metric("off_data_points"), 0);

  touchcloud::test::StageHarness wide(
      "surface_sampler", spike_params({{"near_data", std::string("error")}, {"near_data_margin_mm", 8.5}}));
  EXPECT_EQ(sample_spike(wide, flat_points(0, 10))->size(), 33u);

  touchcloud::test::StageHarness unwired("surface_sampler", spike_params({{"near_data", std::string("error")}}));
  unwired.configure();
  EXPECT_EQ(unwired.process_one<CloudConstPtr>({{"surface", SurfaceModelPtr(std::make_shared<SpikedSurface>())}},
                                               "cloud")
                ->size(),
            33u);
  EXPECT_EQ(unwired.record().metrics.count("stage.off_data_points"), 0u);
}
