// side_touch in pipelines/closed_object_all_sides.yaml on the shipped torus
// (bottom on the table, 30 mm tall): touches from any side, each checked
// against the scene's object before it is made; on a turntable, the chosen
// approach turned with the object. And on the shipped mug's inner wall, which
// no press against its normal reaches, oblique presses.
#include <cmath>
#include <fstream>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "stage_harness.hpp"
#include "test_support.hpp"
#include "touchcloud/types/implicit_model.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/touch.hpp"

namespace fs = std::filesystem;
using touchcloud::test::run_cli;

namespace {

const fs::path kTorusScene = touchcloud::test::source_dir() / "sample_clouds/closed_objects/torus/scene.yaml";

// The shipped torus's scene with `turntable` added (its mesh found from `dir`).
fs::path torus_on_turntable(const fs::path& dir, const std::string& turntable) {
  std::string text = touchcloud::test::read_file(kTorusScene);
  const std::string mesh = "mesh: torus.ply";
  text.replace(text.find(mesh), mesh.size(), "mesh: " + (kTorusScene.parent_path() / "torus.ply").string());
  const fs::path scene = dir / "torus_turntable.yaml";
  std::ofstream(scene) << text << turntable;
  return scene;
}

nlohmann::json run_torus(const fs::path& out, const std::vector<std::string>& sets,
                         const fs::path& scene = kTorusScene) {
  std::vector<std::string> args{"run",
                                (touchcloud::test::source_dir() / "pipelines/closed_object_all_sides.yaml").string(),
                                "--scene", scene.string(), "--seed", "1", "--quiet", "--out", out.string()};
  for (const auto& s : sets) args.insert(args.end(), {"--set", s});
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(touchcloud::test::read_file(out / "summary.json"));
}
double metric(const nlohmann::json& s, const std::string& key) { return s["metrics"][key]["value"].get<double>(); }

}  // namespace

// A start tilted to the horizontal: the 65 mm dome beside a 30 mm tall torus
// would sweep below the table, so all four side approaches (each aimed at
// the centre and at four points beside it) are refused for the table before
// they are made, and the touches go elsewhere. A refused touch is a first
// choice refused: four start touches, plus at most one per touch made after
// them; the approaches tried, 5 aims each, are counted apart.
TEST(SideTouch, ApproachesThatWouldMeetTheTableAreRefusedAndCounted) {
  touchcloud::test::TempDir dir;
  const nlohmann::json s = run_torus(dir / "flat", {"explore.max_iterations=3", "plan.start_tilt_deg=90"});
  EXPECT_EQ(metric(s, "plan.touches_planned"), 3);
  EXPECT_GE(metric(s, "plan.refused_table"), 4);
  EXPECT_LE(metric(s, "plan.refused_touches"), 4 + 2);
  EXPECT_GE(metric(s, "plan.refused_candidates"), 4 * 5);
  EXPECT_EQ(metric(s, "plan.refused_touches"), metric(s, "plan.refused_table") + metric(s, "plan.refused_object") +
                                                   metric(s, "plan.refused_workspace") +
                                                   metric(s, "plan.refused_nothing"));
  EXPECT_EQ(metric(s, "sensor.touches"), 3);
}

// On a turntable the start's approaches, planned in the object's frame, are
// turned with the object for the touch they are made in: the first straight
// down onto the torus's centre, which a quarter turn about (30, 0) has moved
// to (30, -30); the second, 45 degrees from the vertical from the object's +x
// side, then comes from the base frame's +y side.
TEST(SideTouch, OnATurntableTheApproachTurnsWithTheObject) {
  using namespace touchcloud;
  test::TempDir dir;
  const fs::path scene = torus_on_turntable(dir.path(), "turntable: {centre_mm: [30, 0], angles_deg: [90]}\n");
  test::StageHarness h("side_touch", {{"scene", scene.string()}}, "plan");
  h.configure();
  const auto first = h.process_one<TouchTarget>({}, "target");
  ASSERT_TRUE(first.base_from_approach);
  EXPECT_NEAR((first.base_from_approach->translation().head<2>() - Eigen::Vector2d(30, -30)).norm(), 0.0, 1e-9);
  const auto second = h.process_one<TouchTarget>({}, "target");
  ASSERT_TRUE(second.base_from_approach);
  const Eigen::Vector3d back = second.base_from_approach->linear().col(2);  // the approach frame's z: against the press
  EXPECT_NEAR((back - Eigen::Vector3d(0, std::sqrt(0.5), std::sqrt(0.5))).norm(), 0.0, 1e-9) << back.transpose();
}

// The shipped pipeline on a turntable that turns the torus a quarter turn
// between touches: every touch is made, the fit closes round them.
TEST(SideTouch, ATurntableSceneIsTouchedFromSeveralSides) {
  touchcloud::test::TempDir dir;
  const fs::path scene = torus_on_turntable(dir.path(), "turntable: {centre_mm: [10, 0], step_deg: 90}\n");
  const nlohmann::json s = run_torus(dir / "turning", {"explore.max_iterations=6"}, scene);
  EXPECT_EQ(metric(s, "plan.touches_planned"), 6);
  EXPECT_EQ(metric(s, "sensor.touches"), 6);
  EXPECT_LT(metric(s, "score.chamfer_est_to_gt"), 5.0);
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

namespace {

// Points every 10 degrees round the shipped mug's body's axis (x = -13.5 mm),
// `radius_mm` from it, at each of `heights_mm`.
touchcloud::CloudConstPtr ring_points(double radius_mm, const std::vector<double>& heights_mm) {
  auto cloud = std::make_shared<touchcloud::PointCloud>();
  for (int deg = 0; deg < 360; deg += 10)
    for (const double z : heights_mm)
      cloud->push_back(pcl::PointXYZ(static_cast<float>(-13.5 + radius_mm * std::cos(deg * M_PI / 180)),
                                     static_cast<float>(radius_mm * std::sin(deg * M_PI / 180)), static_cast<float>(z)));
  return cloud;
}

// The shipped mug's inner wall (a cylinder of radius 36 mm about its body's
// axis at x = -13.5 mm) as a model predicts it, and points on it from 20 to
// 60 mm up: every candidate faces the axis.
class MugInnerWall final : public touchcloud::ImplicitModel {
 public:
  static Eigen::Vector2d axis() { return {-13.5, 0}; }
  static constexpr double kRadiusMm = 36;
  Eigen::VectorXd mean(const Eigen::MatrixX3d& p) const override {
    return kRadiusMm - (p.leftCols<2>().rowwise() - axis().transpose()).rowwise().norm().array();
  }
  Eigen::VectorXd variance(const Eigen::MatrixX3d& p) const override { return Eigen::VectorXd::Ones(p.rows()); }
  static touchcloud::CloudConstPtr points() { return ring_points(kRadiusMm, {20, 30, 40, 50, 60}); }
};

}  // namespace

// A cup's inner wall cannot be pressed against its normal: the far wall
// stands in the way of every such approach, so the planner finds nothing
// to reach and stops. With oblique_deg it turns the press towards straight
// down and reaches the wall through the opening.
TEST(SideTouch, AnInnerWallHiddenAlongItsNormalIsPressedObliquely) {
  using namespace touchcloud;
  const fs::path scene = test::source_dir() / "sample_clouds/closed_objects/mug/scene_fingertip.yaml";
  const ImplicitModelPtr wall = std::make_shared<MugInnerWall>();
  for (const bool oblique : {false, true}) {
    std::map<std::string, ParamValue> params{{"scene", scene.string()}, {"start_touches", std::int64_t{1}}};
    if (oblique) params["oblique_deg"] = std::vector<double>{30, 45, 60};
    test::StageHarness h("side_touch", params, "plan");
    h.configure();
    h.process_one<TouchTarget>({}, "target");  // the start
    const auto out = h.process({{"implicit", wall}, {"surface_points", MugInnerWall::points()}}, {"target", "done"});
    const bool done = std::any_cast<bool>(out.at("done"));
    h.finish();
    if (!oblique) {
      EXPECT_TRUE(done);
      EXPECT_EQ(h.metric("oblique_touches"), 0);
      continue;
    }
    ASSERT_FALSE(done);
    EXPECT_EQ(h.metric("oblique_touches"), 1);
    const auto target = std::any_cast<TouchTarget>(out.at("target"));
    ASSERT_TRUE(target.base_from_approach);
    const Eigen::Vector3d press = -target.base_from_approach->linear().col(2);
    const Eigen::Vector3d at = target.base_from_approach->translation();
    const Eigen::Vector2d radial = (at.head<2>() - MugInnerWall::axis()).normalized();
    EXPECT_NEAR((at.head<2>() - MugInnerWall::axis()).norm(), MugInnerWall::kRadiusMm, 1e-3);
    EXPECT_LT(press.z(), 0);  // heading down into the cup
    // Turned at least the first 30 degrees from the press against the wall's normal (outwards, along `radial`).
    EXPECT_GE(std::acos(press.dot(Eigen::Vector3d(radial.x(), radial.y(), 0))) * 180 / M_PI, 30 - 1e-6)
        << press.transpose();
  }
}

namespace {

// The shipped mug's outer wall (radius 40 mm about x = -13.5 mm) as a model
// predicts it, least certain at its foot: points all round it 3 mm and 50 mm up.
class MugOuterWall final : public touchcloud::ImplicitModel {
 public:
  Eigen::VectorXd mean(const Eigen::MatrixX3d& p) const override {
    return (p.leftCols<2>().rowwise() - MugInnerWall::axis().transpose()).rowwise().norm().array() - 40.0;
  }
  Eigen::VectorXd variance(const Eigen::MatrixX3d& p) const override {
    return (p.col(2).array() < 10).select(Eigen::VectorXd::Constant(p.rows(), 50.0), Eigen::VectorXd::Ones(p.rows()));
  }
  static touchcloud::CloudConstPtr points() { return ring_points(40, {3, 50}); }
};

}  // namespace

// The wall's foot, where the object stands on the table, is where the model
// knows least; an oblique press aimed at it is made (and meets the wall
// higher up). With table_clearance_mm the planner leaves the foot alone and
// presses the wall above it.
TEST(SideTouch, CandidatesAtTheObjectsFootAreSkippedAboveTheTableClearance) {
  using namespace touchcloud;
  const fs::path scene = test::source_dir() / "sample_clouds/closed_objects/mug/scene_fingertip.yaml";
  const ImplicitModelPtr wall = std::make_shared<MugOuterWall>();
  for (const double clearance : {0.0, 10.0}) {
    test::StageHarness h("side_touch",
                         {{"scene", scene.string()},
                          {"start_touches", std::int64_t{1}},
                          {"oblique_deg", std::vector<double>{20, 40, 60, 75}},
                          {"table_clearance_mm", clearance}},
                         "plan");
    h.configure();
    h.process_one<TouchTarget>({}, "target");  // the start
    const auto out = h.process({{"implicit", wall}, {"surface_points", MugOuterWall::points()}}, {"target", "done"});
    h.finish();
    ASSERT_FALSE(std::any_cast<bool>(out.at("done")));
    const double z = h.metric("target_z_mm");
    if (clearance == 0) {
      EXPECT_EQ(z, 3.0) << "the foot, least certain, is chosen";
      EXPECT_EQ(h.metric("low_candidates"), 0);
    } else {
      EXPECT_EQ(z, 50.0);
      EXPECT_EQ(h.metric("low_candidates"), 36) << "every point at the foot was drawn and skipped";
    }
  }
}

TEST(SideTouch, AnObliqueTurnBeyondTheHorizonIsRefusedNamingIt) {
  using namespace touchcloud;
  const fs::path scene = test::source_dir() / "sample_clouds/closed_objects/mug/scene_fingertip.yaml";
  for (const double deg : {0.0, 120.0}) {
    test::StageHarness h("side_touch", {{"scene", scene.string()}, {"oblique_deg", std::vector<double>{30, deg}}}, "plan");
    try {
      h.configure();
      ADD_FAILURE() << deg << " degrees taken";
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find("oblique_deg"), std::string::npos) << e.what();
    }
  }
}
