// Touches from any side (touch_simulation.hpp, objects/approach_view.hpp):
// the palm's pose is a full rigid transform, the press goes along its normal,
// and the gel meets the object as a vertical press would in the palm's frame.
// The contact markers (the simulator's truth: they rise onto the mesh) lie on
// the analytic sphere and torus within 0.02 mm: the test meshes' facets lie
// within 0.01 mm of them, and the rest is rounding.
#include <gtest/gtest.h>

#include <vector>

#include "closed_shape_fixture.hpp"
#include "touchcloud/gp/implicit_surface.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

constexpr double kOnSurfaceMm = 0.02;
const Eigen::Vector3d kSphereCentre(0, 0, 40);  // on a stand, 10 mm above the table
constexpr double kSphereRadius = 30;
const Eigen::Vector3d kTorusCentre(0, 0, 25);
constexpr double kRing = 35, kTube = 15;

double sphere_distance(const Eigen::Vector3d& p) { return std::abs((p - kSphereCentre).norm() - kSphereRadius); }
double torus_distance(const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p - kTorusCentre;
  return std::abs(Eigen::Vector2d(q.head<2>().norm() - kRing, q.z()).norm() - kTube);
}

// The contact markers of the pressed frame, in the object's frame.
std::vector<Eigen::Vector3d> contacts(const simulation::GelStereoSimulation& sim) {
  std::vector<Eigen::Vector3d> out;
  const simulation::GelState& gel = sim.gel();
  for (std::size_t i = 0; i < gel.overlapping.size(); ++i)
    if (gel.overlapping[i]) out.push_back(gel.markers_base_mm[i]);
  return out;
}

// A touch along `direction` through `point`; its contact markers.
std::vector<Eigen::Vector3d> touch_along(simulation::GelStereoSimulation& sim, const Eigen::Vector3d& point,
                                         const Eigen::Vector3d& direction) {
  press_touch(sim, simulation::PressTarget({0, 0}, simulation::approach_frame(point, direction)));
  return contacts(sim);
}

const std::vector<Eigen::Vector3d> kSideDirections = {
    {-1, 0, 0}, {0, 1, 0}, {-1, -1, -std::sqrt(2.0)},  // from +x, from -y, 45 degrees down from (+x, +y)
};

}  // namespace

TEST(TouchFromAnySide, SphereContactsLieOnTheSphereFromEverySide) {
  TempDir dir;
  simulation::GelStereoSimulation sim(closed_scene(dir, sphere_obj(kSphereRadius), kSphereCentre), 1);
  for (const Eigen::Vector3d& d : kSideDirections) {
    SCOPED_TRACE("direction " + std::to_string(d.x()) + ", " + std::to_string(d.y()) + ", " + std::to_string(d.z()));
    const auto points = touch_along(sim, kSphereCentre, d);
    ASSERT_GT(points.size(), 50u);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : points) {
      EXPECT_LT(sphere_distance(p), kOnSurfaceMm);
      mean += p / static_cast<double>(points.size());
    }
    // The patch is where the palm came from: the centre's side against the approach.
    EXPECT_GT((mean - kSphereCentre).normalized().dot(-d.normalized()), 0.99);
    // The pose reported: the sensor's z is the press direction.
    EXPECT_GT(sim.frame().reported_base_from_sensor.linear().col(2).dot(d.normalized()), 1 - 1e-12);
  }
}

TEST(TouchFromAnySide, TorusContactsLieOnTheTorusFromEverySide) {
  TempDir dir;
  simulation::GelStereoSimulation sim(closed_scene(dir, torus_obj(kRing, kTube), kTorusCentre), 1);
  const Eigen::Vector3d tube_centre = kTorusCentre + Eigen::Vector3d(kRing, 0, 0);
  for (const Eigen::Vector3d& d : kSideDirections) {
    SCOPED_TRACE("direction " + std::to_string(d.x()));
    const Eigen::Vector3d through = d.x() < 0 ? tube_centre : kTorusCentre + Eigen::Vector3d(0, -kRing, 0);
    const auto points = touch_along(sim, through, d);
    ASSERT_GT(points.size(), 30u);
    for (const auto& p : points) EXPECT_LT(torus_distance(p), kOnSurfaceMm);
  }
}

TEST(TouchFromAnySide, ApproachFrameAtTheBaseFrameIsTheVerticalPress) {
  TempDir dir;
  const simulation::Scene scene = closed_scene(dir, sphere_obj(kSphereRadius), kSphereCentre);
  simulation::GelStereoSimulation from_above(scene, 1), framed(scene, 1);
  const auto& a = press_touch(from_above, simulation::PressTarget(Eigen::Vector2d(5, -3)));
  const auto& b = press_touch(framed, simulation::PressTarget(Eigen::Vector2d(5, -3), Eigen::Isometry3d::Identity()));
  EXPECT_EQ(a.touch.frame_in_touch, b.touch.frame_in_touch);
  EXPECT_TRUE(a.reported_base_from_sensor.isApprox(b.reported_base_from_sensor, 1e-12));
  const auto& ga = from_above.gel().markers_base_mm;
  const auto& gb = framed.gel().markers_base_mm;
  ASSERT_EQ(ga.size(), gb.size());
  // The view lifts the mesh into its own frame and back: the same to rounding.
  for (std::size_t i = 0; i < ga.size(); ++i) EXPECT_LT((ga[i] - gb[i]).norm(), 1e-9) << i;
}

// A turntable turned 90 degrees under a touch from above gives the same
// contact, in the object's frame, as the palm turned -90 degrees about the
// same axis with the object standing still.
TEST(TouchFromAnySide, TurntableQuarterTurnIsThePalmTurnedBack) {
  TempDir table_dir, still_dir;
  // The torus off the axis, so that turning it moves it.
  const Eigen::Vector3d off(20, 0, 25);
  const std::string turntable = "turntable: {centre_mm: [0, 0], angles_deg: [90]}\n";
  simulation::GelStereoSimulation on_table(closed_scene(table_dir, torus_obj(kRing, kTube), off, turntable), 1);
  simulation::GelStereoSimulation still(closed_scene(still_dir, torus_obj(kRing, kTube), off), 1);
  const Eigen::Vector2d xy(0, 50);  // over the tube once the torus has turned: (20 + 35, 0) -> (0, 55)
  const auto& a = press_touch(on_table, simulation::PressTarget(xy));
  Eigen::Isometry3d palm_back = Eigen::Isometry3d::Identity();
  palm_back.linear() = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const auto& b = press_touch(still, simulation::PressTarget(xy, palm_back));
  EXPECT_TRUE(a.reported_base_from_sensor.isApprox(b.reported_base_from_sensor, 1e-12));
  const auto ca = contacts(on_table), cb = contacts(still);
  ASSERT_GT(ca.size(), 30u);
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t i = 0; i < ca.size(); ++i) EXPECT_LT((ca[i] - cb[i]).norm(), 1e-9);
  // In the object's frame (the scene's torus at angle 0), on that torus: the
  // ground truth needs no turning.
  for (const auto& p : ca) {
    const Eigen::Vector3d q = p - off;
    EXPECT_LT(std::abs(Eigen::Vector2d(q.head<2>().norm() - kRing, q.z()).norm() - kTube), kOnSurfaceMm);
  }
  // The robot's own pose stays in the base frame: straight down at (0, 50).
  EXPECT_NEAR(a.touch.base_from_sensor.translation().y(), 50, 1e-9);
  EXPECT_NEAR(a.reported_base_from_sensor.translation().x(), 50, 1e-9);  // turned back by -90 degrees
}

TEST(TouchFromAnySide, TurntableStepsTurnPerTouch) {
  TempDir dir;
  simulation::Scene scene = closed_scene(dir, sphere_obj(kSphereRadius), kSphereCentre,
                                         "turntable: {centre_mm: [10, 0], step_deg: 30}\n");
  ASSERT_TRUE(scene.turntable);
  EXPECT_DOUBLE_EQ(scene.turntable->angle_deg(3), 90.0);
  const Eigen::Vector3d moved = scene.turntable->base_from_object(3) * Eigen::Vector3d(20, 0, 5);
  EXPECT_TRUE(moved.isApprox(Eigen::Vector3d(10, 10, 5), 1e-12));
}

TEST(TouchFromAnySide, TurntableNeedsOneOfAnglesOrStep) {
  TempDir dir;
  EXPECT_NE(input_error([&] { closed_scene(dir, sphere_obj(10), kSphereCentre, "turntable: {centre_mm: [0, 0]}\n"); })
                .find("turntable.step_deg: is missing"),
            std::string::npos);
  EXPECT_NE(input_error([&] {
              closed_scene(dir, sphere_obj(10), kSphereCentre, "turntable: {angles_deg: [0, 90], step_deg: 10}\n");
            }).find("set one"),
            std::string::npos);
  write_file(dir / "plane.yaml", "object: " + kPlaneObject + "\nturntable: {step_deg: 10}\n");
  EXPECT_NE(input_error([&] { simulation::load_scene(dir / "plane.yaml"); }).find("turns a mesh object"),
            std::string::npos);
}

TEST(TouchFromAnySide, ASideTouchOfAnAnalyticObjectIsRefused) {
  TempDir dir;
  simulation::GelStereoSimulation sim(plane_scene(dir, "[contact]"), 1);
  const std::string what = input_error(
      [&] { sim.step(simulation::PressTarget({0, 0}, simulation::approach_frame({0, 0, 10}, {-1, 0, -1})), false); });
  EXPECT_NE(what.find("needs a mesh object"), std::string::npos) << what;
}

// Touched from 14 sides (faces and corners of a cube), the sphere fitted as
// an implicit surface (gp, thin plate) has its zero level set within 0.05 mm
// of radius 30 mm along 26 rays from the centre (0.015 mm measured): the
// contacts are exact (above); between the touches the GP's mean deviates.
TEST(TouchFromAnySide, SphereRadiusFromAnImplicitSurfaceOfSideTouches) {
  TempDir dir;
  simulation::GelStereoSimulation sim(closed_scene(dir, sphere_obj(kSphereRadius), kSphereCentre), 1);
  gp::ImplicitSurface surface;
  std::vector<Eigen::Vector3d> rays;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) rays.emplace_back(Eigen::Vector3d(x, y, z).normalized());
  for (const Eigen::Vector3d& ray : rays) {
    if ((ray.array().abs() > 0).count() == 2) continue;  // 6 faces + 8 corners: 14 touches
    const auto points = touch_along(sim, kSphereCentre, -ray);
    gp::ImplicitTouch touch;
    const int every = 4;  // a quarter of each patch keeps the exact GP small
    touch.points_mm.resize((static_cast<Eigen::Index>(points.size()) + every - 1) / every, 3);
    for (std::size_t i = 0; i < points.size(); i += every)
      touch.points_mm.row(static_cast<Eigen::Index>(i / every)) = points[i].transpose();
    // The palm's normal, out of the object: against the sensor's z.
    const Eigen::Vector3d out = -sim.frame().reported_base_from_sensor.linear().col(2);
    touch.normals = out.transpose().replicate(touch.points_mm.rows(), 1);
    surface.add(touch);
  }
  for (const Eigen::Vector3d& ray : rays) {
    // The zero crossing along the ray, bisected between 20 and 40 mm.
    double lo = 20, hi = 40;
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      Eigen::MatrixX3d q(1, 3);
      q.row(0) = (kSphereCentre + mid * ray).transpose();
      (surface.mean(q)(0) > 0 ? hi : lo) = mid;
    }
    EXPECT_NEAR(0.5 * (lo + hi), kSphereRadius, 0.05) << ray.transpose();
  }
}

TEST(TouchFromAnySide, AnApproachFrameThatIsNotRigidIsRefused) {
  TempDir dir;
  simulation::GelStereoSimulation sim(closed_scene(dir, sphere_obj(kSphereRadius), kSphereCentre), 1);
  Eigen::Isometry3d stretched = simulation::approach_frame(kSphereCentre, {-1, 0, 0});
  stretched.linear() *= 1.1;
  const std::string what = input_error([&] { sim.step(simulation::PressTarget({0, 0}, stretched), false); });
  EXPECT_NE(what.find("not a rigid transform"), std::string::npos) << what;
}

TEST(TouchFromAnySide, ATouchThatMissesTheObjectAndTheTableFails) {
  TempDir dir;
  simulation::GelStereoSimulation sim(closed_scene(dir, sphere_obj(kSphereRadius), kSphereCentre), 1);
  // Horizontal, 100 mm above the sphere: nothing on its line.
  const simulation::PressTarget past({0, 0}, simulation::approach_frame(kSphereCentre + Eigen::Vector3d(0, 0, 100), {-1, 0, 0}));
  try {
    press_touch(sim, past);
    ADD_FAILURE() << "no RunError";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("misses the object and the table"), std::string::npos) << e.what();
  }
}
