// The object seen along a press from any side (approach_view.hpp) and the
// reach check of such a touch (reach_check.hpp: refuse_approach).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "closed_shape_fixture.hpp"
#include "touchcloud/simulation/objects/reach_check.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

const Eigen::Vector3d kOnTable(0, 0, 15);  // on the table
constexpr double kRingR = 35, kTubeR = 15;

scoring::TriangleMesh placed_torus(const TempDir& dir) {
  return read_placed_object_mesh(closed_scene(dir, torus_obj(kRingR, kTubeR), kOnTable).object);
}

}  // namespace

TEST(ApproachView, SeesTheObjectAlongThePressAndTheTableWhereItFacesIt) {
  TempDir dir;
  const auto mesh = placed_torus(dir);
  // From +x through the tube's centre: the outer wall 15 mm from it.
  const Eigen::Isometry3d from_x = simulation::approach_frame(kOnTable + Eigen::Vector3d(kRingR, 0, 0), {-1, 0, 0});
  const simulation::ApproachView side(mesh, from_x.inverse());
  EXPECT_NEAR(side.height_mm({0, 0}), kTubeR, 0.01);
  EXPECT_FALSE(side.table_height_mm({0, 0}));  // edge-on: not faced
  EXPECT_LT(side.height_mm({0, 200}), -kRingR);  // beside the torus: the floor behind it
  // 45 degrees down beside the torus: the table.
  const Eigen::Isometry3d down45 = simulation::approach_frame({100, 0, 0}, {-1, 0, -1});
  const simulation::ApproachView oblique(mesh, down45.inverse());
  ASSERT_TRUE(oblique.table_height_mm({0, 0}));
  EXPECT_NEAR(*oblique.table_height_mm({0, 0}), 0.0, 1e-9);  // the frame's origin lies on the table
  EXPECT_NEAR(oblique.height_mm({0, 0}), 0.0, 1e-9);
  EXPECT_NEAR(oblique.overlap_mm({0, 0}, -1.0), 1.0, 1e-9);
}

TEST(ApproachReach, FromBelowTheTableIsRefusedForTheTable) {
  TempDir dir;
  const auto mesh = placed_torus(dir);
  simulation::ApproachLimits limits;
  const Eigen::Isometry3d up = simulation::approach_frame(kOnTable + Eigen::Vector3d(kRingR, 0, 0), {0, 0, 1});
  const simulation::ApproachView view(mesh, up.inverse());
  const auto refused = simulation::refuse_approach(view, up, {0, 0}, std::nullopt, limits);
  ASSERT_TRUE(refused);
  EXPECT_STREQ(simulation::to_string(*refused), "table");
}

TEST(ApproachReach, IntoTheHoleThroughTheRingIsRefusedForTheObject) {
  TempDir dir;
  // On a stand 30 mm high, so that a horizontal palm clears the table.
  const Eigen::Vector3d centre(0, 0, 45);
  const auto mesh = read_placed_object_mesh(closed_scene(dir, torus_obj(kRingR, kTubeR), centre).object);
  // Horizontally from +x through the axis, meant for the hole's far wall
  // (x = -20: z = -20 in the press frame); the ring's outer wall at x = +50
  // stops the gel 70 mm before it.
  const Eigen::Isometry3d from_x = simulation::approach_frame(centre, {-1, 0, 0});
  const simulation::ApproachView view(mesh, from_x.inverse());
  const simulation::ApproachLimits limits;
  const auto refused = simulation::refuse_approach(view, from_x, {0, 0}, -(kRingR - kTubeR), limits);
  ASSERT_TRUE(refused);
  EXPECT_STREQ(simulation::to_string(*refused), "object");
  // Meant for the outer wall it meets first, the same approach is made.
  EXPECT_FALSE(simulation::refuse_approach(view, from_x, {0, 0}, kRingR + kTubeR, limits));
}

TEST(ApproachReach, ATiltBeyondTheRobotsIsRefusedForTheWorkspace) {
  TempDir dir;
  const auto mesh = placed_torus(dir);
  // 45 degrees down through the tube's centre: onto its upper outer side.
  const Eigen::Isometry3d oblique = simulation::approach_frame(kOnTable + Eigen::Vector3d(kRingR, 0, 0), {-1, 0, -1});
  const simulation::ApproachView view(mesh, oblique.inverse());
  EXPECT_FALSE(simulation::refuse_approach(view, oblique, {0, 0}, std::nullopt, simulation::ApproachLimits{}));
  simulation::ApproachLimits upright;
  upright.max_tilt_deg = 30;
  const auto refused = simulation::refuse_approach(view, oblique, {0, 0}, std::nullopt, upright);
  ASSERT_TRUE(refused);
  EXPECT_STREQ(simulation::to_string(*refused), "workspace");
}

// What side_touch relies on to skip building a view: a touch tilted past the
// robot's limit is refused whatever it meets (for the tilt, or for a reason
// checked before it), and one within the limit is never refused for it.
TEST(ApproachReach, EveryApproachTiltedPastTheLimitIsRefused) {
  TempDir dir;
  const auto mesh = placed_torus(dir);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> offset(-60.0, 60.0);
  int tilted = 0, within = 0, refused_within = 0;
  for (const double max_tilt : {30.0, 90.0, 120.0}) {
    simulation::ApproachLimits limits;
    limits.max_tilt_deg = max_tilt;
    for (int i = 0; i < 150; ++i) {
      const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
      const Eigen::Vector3d at = kOnTable + Eigen::Vector3d(offset(rng), offset(rng), 0.5 * offset(rng));
      const Eigen::Isometry3d frame = simulation::approach_frame(at, d);
      const simulation::ApproachView view(mesh, frame.inverse(), limits.gel_radius_mm + 1.0);
      const auto why = simulation::refuse_approach(view, frame, {0, 0}, std::nullopt, limits);
      const double tilt = std::acos(std::clamp(-d.normalized().z(), -1.0, 1.0)) * 180.0 / M_PI;
      if (simulation::tilts_beyond_reach(frame, limits)) {
        ++tilted;
        EXPECT_GT(tilt, max_tilt - 1e-6);
        EXPECT_TRUE(why) << "direction " << d.transpose() << " at " << at.transpose();
      } else {
        ++within;
        EXPECT_LE(tilt, max_tilt + 1e-6);
        if (why) {  // no workspace box: within the tilt limit, never for the workspace
          ++refused_within;
          EXPECT_NE(*why, simulation::ReachRefusal::Workspace) << "direction " << d.transpose();
        }
      }
    }
  }
  // Both kinds, and refusals of the others for other reasons, were met.
  EXPECT_GT(tilted, 100);
  EXPECT_GT(within, 100);
  EXPECT_GT(refused_within, 10);
}

// The press goes on past first contact: a press onto the table beside the
// object would push the gel into it.
TEST(ApproachReach, APressIntoTheTableIsRefusedForTheTable) {
  TempDir dir;
  const auto mesh = placed_torus(dir);
  const Eigen::Isometry3d beside = simulation::approach_frame({100, 0, 0}, {0, 0, -1});
  const simulation::ApproachView view(mesh, beside.inverse());
  simulation::ApproachLimits limits;
  const auto refused = simulation::refuse_approach(view, beside, {0, 0}, std::nullopt, limits);
  ASSERT_TRUE(refused);
  EXPECT_STREQ(simulation::to_string(*refused), "table");
  limits.press_mm = 0;  // only touching it
  EXPECT_FALSE(simulation::refuse_approach(view, beside, {0, 0}, std::nullopt, limits));
}

// The shipped mug's two scenes (sample_clouds/closed_objects/mug). A press
// straight down at its footprint's centre, 13.5 mm beside the cup's axis:
// the Palm's 65 mm dome stops on the rim (z = 90 mm), the 20 mm fingertip
// (scene_fingertip.yaml) goes in and presses the inside floor (z = 6 mm).
// A press onto the floor 25 mm from the axis: refused for the object with
// the dome (it meets the rim first), reachable with the fingertip.
TEST(ShippedMug, TheFingertipPressesInsideWhereThePalmsDomeStopsOnTheRim) {
  const std::filesystem::path folder = source_dir() / "sample_clouds/closed_objects/mug";
  for (const bool fingertip : {false, true}) {
    SCOPED_TRACE(fingertip ? "fingertip" : "palm");
    const simulation::Scene scene = simulation::load_scene(folder / (fingertip ? "scene_fingertip.yaml" : "scene.yaml"));
    simulation::GelStereoSimulation sim(scene, 1);
    press_touch(sim, simulation::PressTarget(Eigen::Vector2d(0, 0)));
    double lowest = std::numeric_limits<double>::infinity();
    int touching = 0;
    for (std::size_t i = 0; i < sim.gel().overlapping.size(); ++i)
      if (sim.gel().overlapping[i]) {
        lowest = std::min(lowest, sim.gel().markers_base_mm[i].z());
        ++touching;
      }
    ASSERT_GT(touching, 10);
    if (fingertip)
      EXPECT_NEAR(lowest, 6.0, 0.05);
    else
      EXPECT_GT(lowest, 89.0);

    simulation::ApproachLimits limits;
    limits.gel_radius_mm = scene.sensor.gel.radius_mm();
    const Eigen::Isometry3d down = simulation::approach_frame({-13.5 + 25, 0, 6}, {0, 0, -1});
    const simulation::ApproachView view(read_placed_object_mesh(scene.object), down.inverse());
    const auto refused = simulation::refuse_approach(view, down, {0, 0}, 0.0, limits);
    if (fingertip)
      EXPECT_FALSE(refused) << simulation::to_string(*refused);
    else
      EXPECT_EQ(refused, simulation::ReachRefusal::Object);
  }
}

// A view within the gel's disc (what side_touch's reach check builds for
// every candidate) reads only the triangles near the approach, and must give
// the full view's heights there bit for bit, and the same refusals. Shipped
// mug and torus, approaches from 200 directions aimed round the object.
TEST(ApproachView, WithinARadiusItGivesTheFullViewsHeightsAndRefusalsThere) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const char* shape : {"mug", "torus"}) {
    SCOPED_TRACE(shape);
    const simulation::Scene scene =
        simulation::load_scene(source_dir() / "sample_clouds/closed_objects" / shape / "scene_fingertip.yaml");
    const scoring::TriangleMesh mesh = read_placed_object_mesh(scene.object);
    simulation::ApproachLimits limits;
    limits.gel_radius_mm = scene.sensor.gel.radius_mm();
    int refused = 0;
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d aim(40 * unit(rng), 30 * unit(rng), 45 + 40 * unit(rng));
      Eigen::Vector3d direction(unit(rng), unit(rng), unit(rng));
      if (direction.norm() < 0.1) direction = -Eigen::Vector3d::UnitZ();
      const Eigen::Isometry3d frame = simulation::approach_frame(aim, direction);
      const simulation::ApproachView full(mesh, frame.inverse());
      const simulation::ApproachView near(mesh, frame.inverse(), limits.gel_radius_mm + 1.0);
      for (double x = -limits.gel_radius_mm; x <= limits.gel_radius_mm; x += 0.5)
        for (double y = -limits.gel_radius_mm; y <= limits.gel_radius_mm; y += 0.5) {
          if (std::hypot(x, y) > limits.gel_radius_mm) continue;
          ASSERT_EQ(near.height_mm({x, y}), full.height_mm({x, y})) << "approach " << i << " at " << x << ", " << y;
        }
      EXPECT_EQ(near.floor_mm(), full.floor_mm());
      const auto why = simulation::refuse_approach(full, frame, {0, 0}, 0.0, limits);
      EXPECT_EQ(simulation::refuse_approach(near, frame, {0, 0}, 0.0, limits), why) << "approach " << i;
      refused += why.has_value();
    }
    // Both kinds of approach were tried: some refused, most not.
    EXPECT_GT(refused, 10);
    EXPECT_LT(refused, 190);
  }
}
