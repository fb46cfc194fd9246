// The implicit surface (a GP on the signed distance) from touch patches of a
// sphere and a torus: its sign inside and outside, the radii it recovers
// along rays from the centre, its variance (never negative, small where
// touched), bordered updates between selections, and the touch sets it
// refuses (no points, no normals where the side cannot be told, bad normals).
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "implicit_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/gp/implicit_surface.hpp"

using namespace touchcloud;
using touchcloud::test::SphereObject;
using touchcloud::test::TorusObject;
using touchcloud::test::one_row;
using touchcloud::test::zero_crossing;

namespace {

gp::ImplicitSurface implicit_fitted(const std::vector<gp::ImplicitTouch>& touches, gp::ImplicitSurfaceOptions o = {}) {
  o.reselect_growth = 1.0;
  o.selection_points = 200;  // selections at 1, 2, 4, 8, ... touches
  gp::ImplicitSurface s(o);
  for (const auto& t : touches) s.add(t);
  return s;
}

// What the model says of a touch it refuses, or "accepted".
std::string refusal(gp::ImplicitSurface& s, const gp::ImplicitTouch& t) {
  try {
    s.add(t);
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return "accepted";
}

}  // namespace

// 40 touches of 5 mm radius spread over a sphere of 20 mm leave no point of it
// farther than about 7 mm from a contact. Along 26 rays the zero crossing lies
// within 0.25 mm of the true radius: an eighth of the 2 mm offset, and an
// order of magnitude below the palm's footprint, so that an error of the
// sign or the scale of the signed points would show.
TEST(ImplicitSurface, SphereRadiusAlongRays) {
  const SphereObject sphere;
  for (const auto kernel : {gp::ImplicitKernelKind::thin_plate, gp::ImplicitKernelKind::matern52}) {
    gp::ImplicitSurfaceOptions o;
    o.kernel = kernel;
    const gp::ImplicitSurface s = implicit_fitted(sphere.touches(40), o);
    EXPECT_LT(test::worst_radius_error(s, sphere), 0.25) << gp::to_string(kernel);
  }
}

// The torus's tube (minor radius 8 mm) and its hole: the hole's centre is
// outside although the prior's sphere holds it, and the inner and outer
// walls are found at R - r and R + r within 0.3 mm in eight directions.
TEST(ImplicitSurface, TorusSignAndRadii) {
  const TorusObject torus;
  const gp::ImplicitSurface s = implicit_fitted(torus.touches(12, 6));
  EXPECT_GT(s.mean(one_row(Eigen::Vector3d::Zero()))[0], 0) << "the hole's centre is outside";
  EXPECT_GT(s.mean(one_row({0, 0, 30}))[0], 0);
  EXPECT_GT(s.mean(one_row({60, 0, 0}))[0], 0);
  for (int i = 0; i < 8; ++i) {
    const double u = 2 * std::numbers::pi * (i + 0.25) / 8;
    const Eigen::Vector3d d(std::cos(u), std::sin(u), 0);
    const Eigen::Vector3d tube = torus.major_mm * d;
    EXPECT_LT(s.mean(one_row(tube))[0], 0) << "inside the tube at " << u;
    const double outer = zero_crossing(s, tube, (torus.major_mm + 2 * torus.minor_mm) * d).norm();
    const double inner = zero_crossing(s, tube, 0.5 * (torus.major_mm - torus.minor_mm) * d).norm();
    EXPECT_NEAR(outer, torus.major_mm + torus.minor_mm, 0.3) << u;
    EXPECT_NEAR(inner, torus.major_mm - torus.minor_mm, 0.3) << u;
    EXPECT_NEAR(0.5 * (outer + inner), torus.major_mm, 0.3) << u;
    EXPECT_NEAR(0.5 * (outer - inner), torus.minor_mm, 0.3) << u;
  }
}

// Touched: the variance is near the noise's; untouched (a sphere touched on
// its upper half only): larger below.
TEST(ImplicitSurface, VarianceSmallWhereTouched) {
  const SphereObject sphere;
  std::vector<gp::ImplicitTouch> upper;
  for (const auto& t : sphere.touches(40))
    if (t.normals(0, 2) > 0.2) upper.push_back(t);
  const gp::ImplicitSurface s = implicit_fitted(upper);
  const Eigen::VectorXd top = s.variance(one_row(sphere.centre_mm + Eigen::Vector3d(0, 0, sphere.radius_mm)));
  const Eigen::VectorXd bottom = s.variance(one_row(sphere.centre_mm - Eigen::Vector3d(0, 0, sphere.radius_mm)));
  EXPECT_LT(top[0], 0.05);
  EXPECT_GT(bottom[0], 20 * top[0]);
}

// Noise almost 0: at the training points themselves the prior and the part
// the data explain cancel, and rounding leaves values a little below 0. They
// leave the model as 0, counted.
TEST(ImplicitSurface, VarianceNeverNegative) {
  gp::ImplicitSurfaceOptions o;
  o.kernel = gp::ImplicitKernelKind::matern52;
  o.offset_stride = 1;
  o.min_noise_mm = 1e-7;
  o.max_noise_mm = 1e-7;
  const gp::ImplicitSurface s = implicit_fitted(SphereObject().touches(12), o);
  std::size_t clamped = 0;
  const Eigen::VectorXd v = s.variance(s.contact_points(), &clamped);
  EXPECT_GT(clamped, 0u) << "the case needs values that round below 0";
  EXPECT_GE(v.minCoeff(), 0.0);
  EXPECT_TRUE(v.allFinite());
}

// Between selections a touch extends the factor (a bordered update); the
// model then agrees with one that took the same touches as one block.
TEST(ImplicitSurface, BorderedUpdateBetweenSelections) {
  const auto touches = SphereObject().touches(10);
  gp::ImplicitSurfaceOptions o;
  o.kernel = gp::ImplicitKernelKind::matern52;  // thin_plate selects again where a touch reaches beyond R
  o.reselect_growth = 100;
  o.offset_stride = 1;  // the same signed points whatever the grouping
  gp::ImplicitSurface one_by_one(o), grouped(o);
  EXPECT_EQ(one_by_one.add(touches[0]).path, gp::ImplicitUpdatePath::selected);
  grouped.add(touches[0]);
  gp::ImplicitTouch rest;
  rest.points_mm.resize(0, 3);
  rest.normals.resize(0, 3);
  for (std::size_t i = 1; i < touches.size(); ++i) {
    EXPECT_EQ(one_by_one.add(touches[i]).path, gp::ImplicitUpdatePath::bordered) << i;
    const Eigen::Index k = touches[i].points_mm.rows(), at = rest.points_mm.rows();
    rest.points_mm.conservativeResize(at + k, 3);
    rest.normals.conservativeResize(at + k, 3);
    rest.points_mm.bottomRows(k) = touches[i].points_mm;
    rest.normals.bottomRows(k) = touches[i].normals;
  }
  EXPECT_EQ(grouped.add(rest).path, gp::ImplicitUpdatePath::bordered);
  EXPECT_EQ(one_by_one.training_size(), grouped.training_size());
  const Eigen::MatrixX3d q = SphereObject().touches(25)[7].points_mm * 1.1;
  EXPECT_LT((one_by_one.mean(q) - grouped.mean(q)).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((one_by_one.variance(q) - grouped.variance(q)).cwiseAbs().maxCoeff(), 1e-6);
}

// Without normals a patch's plane normal, turned away from the centroid of
// all the points touched, gives the side: right for a sphere once a first
// touch has said where its surface faces.
TEST(ImplicitSurface, NormalsFromPatchesWhenNoneGiven) {
  const SphereObject sphere;
  std::vector<gp::ImplicitTouch> touches = sphere.touches(40);
  for (std::size_t i = 1; i < touches.size(); ++i) touches[i].normals.resize(0, 3);
  const gp::ImplicitSurface s = implicit_fitted(touches);
  EXPECT_LT(s.mean(one_row(sphere.centre_mm))[0], 0);
  const Eigen::Vector3d d(0.6, 0, 0.8);
  const Eigen::Vector3d p = zero_crossing(s, sphere.centre_mm, sphere.centre_mm + 2 * sphere.radius_mm * d);
  EXPECT_NEAR((p - sphere.centre_mm).norm(), sphere.radius_mm, 0.5);
}

// Touch sets that say nothing about inside and outside are refused, naming
// the touch, and leave the model as it was.
TEST(ImplicitSurface, RefusesEmptyAndDegenerateTouches) {
  gp::ImplicitSurface s{gp::ImplicitSurfaceOptions{}};
  EXPECT_THROW(s.mean(one_row(Eigen::Vector3d::Zero())), InputError);
  gp::ImplicitTouch empty;
  EXPECT_THROW(s.add(empty), InputError);
  auto message = [&](const gp::ImplicitTouch& t) { return refusal(s, t); };
  gp::ImplicitTouch line;
  line.points_mm.resize(5, 3);
  for (int i = 0; i < 5; ++i) line.points_mm.row(i) << i, 2 * i, 3;
  EXPECT_NE(message(line).find("collinear"), std::string::npos) << message(line);
  // A patch alone, or patches of one plane (a table top), without normals.
  gp::ImplicitTouch flat;
  flat.points_mm.resize(9, 3);
  for (int i = 0; i < 9; ++i) flat.points_mm.row(i) << i % 3, i / 3, 0;
  EXPECT_NE(message(flat).find("inside and outside cannot be told apart"), std::string::npos) << message(flat);
  gp::ImplicitTouch flat_with_normals = flat;
  flat_with_normals.normals = Eigen::RowVector3d(0, 0, 1).replicate(9, 1);
  s.add(flat_with_normals);
  gp::ImplicitTouch beside = flat;
  beside.points_mm.col(0).array() += 20;
  EXPECT_NE(message(beside).find("inside and outside cannot be told apart"), std::string::npos) << message(beside);
  gp::ImplicitTouch bad = flat_with_normals;
  bad.normals(3, 2) = 2;
  EXPECT_NE(message(bad).find("normal of point 3 has length 2"), std::string::npos) << message(bad);
  bad.normals.resize(4, 3);
  EXPECT_NE(message(bad).find("4 normals for 9 points"), std::string::npos) << message(bad);
  bad = flat_with_normals;
  bad.points_mm(2, 1) = std::nan("");
  EXPECT_NE(message(bad).find("not finite"), std::string::npos) << message(bad);
  EXPECT_EQ(s.touches(), 1u);
  EXPECT_EQ(s.contact_points().rows(), 9);
}

// The mean on many threads is the mean on one, bit for bit.
TEST(ImplicitSurface, MeanSameOnAnyThreadCount) {
  const gp::ImplicitSurface s = implicit_fitted(SphereObject().touches(6));
  const Eigen::MatrixX3d q = Eigen::MatrixX3d::Random(1000, 3) * 30;
  const Eigen::VectorXd one = s.mean(q, 1), three = s.mean(q, 3);
  EXPECT_EQ(one, three);
}

// A cup's wall touched all round and its floor pressed from above, through
// its mouth: the smooth field closes the mouth (the prior's sphere holds the
// hollow, and nothing touched says otherwise), so a planner would aim at a
// lid that is not there. The press's swept approach opens it: the axis above
// the floor is outside, at its distance from the floor, and the walls stay
// where they were.
TEST(ImplicitSurface, ASweptApproachOpensTheSpaceAPressWentThrough) {
  std::vector<gp::ImplicitTouch> touches = test::cup_and_floor_press(2.5);
  const gp::ImplicitSurface closed = implicit_fitted(touches);
  gp::add_swept_approach(touches.back(), {0, 0, 10}, Eigen::Vector3d::UnitZ(), 80, 4);
  const gp::ImplicitSurface open = implicit_fitted(touches);
  EXPECT_LT(closed.mean(one_row({0, 0, 75}))[0], -5) << "the mouth is closed without the approach";
  for (double z = 14; z <= 90; z += 4)  // at the swept points
    EXPECT_NEAR(open.mean(one_row({0, 0, z}))[0], z - 10, 0.5) << "on the axis at z = " << z;
  for (double deg : {0.0, 30.0, 135.0})
    for (double r : {38.0, 42.0}) {
      const Eigen::MatrixX3d p = one_row(test::CupWall::at(r, deg, 45));
      EXPECT_NEAR(open.mean(p)[0], closed.mean(p)[0], 0.1) << "the wall at radius " << r << ", " << deg << " deg";
    }
}

// Swept points the model cannot take are refused, naming the touch and the
// point, and leave the model as it was.
TEST(ImplicitSurface, RefusesSweptPointsInsideOrNotFinite) {
  gp::ImplicitSurface s{gp::ImplicitSurfaceOptions{}};
  gp::ImplicitTouch t = SphereObject().touch({0, 0, 1});
  EXPECT_THROW(gp::add_swept_approach(t, {0, 0, 60}, {0, 0, 2}, 20, 4), InputError) << "not a unit direction";
  gp::add_swept_approach(t, {5, -3, 60}, {0, 0, 1}, 20, 4);
  ASSERT_EQ(t.free_mm.rows(), 5);
  auto message = [&](const gp::ImplicitTouch& touch) { return refusal(s, touch); };
  gp::ImplicitTouch bad = t;
  bad.free_distance_mm[2] = 0;
  EXPECT_NE(message(bad).find("touch 1: swept point 2 has distance 0"), std::string::npos) << message(bad);
  bad = t;
  bad.free_mm(4, 0) = std::nan("");
  EXPECT_NE(message(bad).find("a swept point is not finite"), std::string::npos) << message(bad);
  bad = t;
  bad.free_distance_mm.conservativeResize(3);
  EXPECT_NE(message(bad).find("3 distances for 5 swept points"), std::string::npos) << message(bad);
  EXPECT_EQ(s.touches(), 0u);
  EXPECT_EQ(message(t), "accepted");
  EXPECT_EQ(s.training_size(), gp::implicit_rows_of(t, s.options()));
}
