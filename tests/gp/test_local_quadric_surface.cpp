// Local quadric surfaces of touched points (gp/local_quadric_surface.hpp):
// a sphere's radius, a thin wall touched densely outside and sparsely
// inside (where the GP's mean thickens the wall), free space, and bad input.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "implicit_fixtures.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/gp/implicit_surface.hpp"
#include "touchcloud/gp/local_quadric_surface.hpp"

namespace touchcloud::gp {
namespace {

struct Touched {
  Eigen::MatrixX3d points = Eigen::MatrixX3d(0, 3), outward = Eigen::MatrixX3d(0, 3);
  std::vector<ImplicitTouch> touches;
  void add(const ImplicitTouch& t) {
    const Eigen::Index from = points.rows(), k = t.points_mm.rows();
    points.conservativeResize(from + k, 3);
    outward.conservativeResize(from + k, 3);
    points.bottomRows(k) = t.points_mm;
    outward.bottomRows(k) = t.normals;
    touches.push_back(t);
  }
};

Touched thin_wall(double step_mm = 0.9, double outer_deg = 15) {
  Touched t;
  for (const ImplicitTouch& touch : test::CupWall().touches(step_mm, outer_deg)) t.add(touch);
  return t;
}

Eigen::Vector3d at_radius(double r, double deg, double z) { return test::CupWall::at(r, deg, z); }

TEST(LocalQuadricSurface, RecoversASpheresRadiusFromTouchesAllRound) {
  const test::SphereObject sphere;
  Touched t;
  for (const ImplicitTouch& touch : sphere.touches(40)) t.add(touch);
  const LocalQuadricSurface surface(t.points, t.outward);
  // Between touches, 2 mm inside and outside: the radius within 0.2 mm.
  Eigen::MatrixX3d q(3, 3);
  const Eigen::Vector3d dir = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  for (int i = 0; i < 3; ++i) q.row(i) = (sphere.centre_mm + (sphere.radius_mm + 2.0 * (i - 1)) * dir).transpose();
  std::vector<bool> covered;
  const Eigen::VectorXd d = surface.value(q, covered);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(covered[static_cast<std::size_t>(i)]) << i;
    EXPECT_NEAR(d[i], 2.0 * (i - 1), 0.2) << "query " << i;
  }
}

TEST(LocalQuadricSurface, KeepsAThinWallThinWhereOnlyItsOuterFaceIsTouchedNearby) {
  const Touched t = thin_wall();
  // Angle 30 degrees, height 45: outer patches 4 mm away across the wall,
  // the nearest inner patch 19 mm away along it.
  Eigen::MatrixX3d q(4, 3);
  q.row(0) = at_radius(33.0, 30, 45).transpose();  // the hollow, 3 mm from the inner face
  q.row(1) = at_radius(38.0, 30, 45).transpose();  // inside the wall
  q.row(2) = at_radius(36.0, 30, 45).transpose();  // the inner face
  q.row(3) = at_radius(43.0, 30, 45).transpose();  // outside
  // With sharp edges the same: the wall's two faces are a convex pair, so
  // the hollow stays outside.
  for (const double edge_deg : {0.0, 60.0}) {
    LocalQuadricOptions options;
    options.edge_deg = edge_deg;
    std::vector<bool> covered;
    const Eigen::VectorXd d = LocalQuadricSurface(t.points, t.outward, options).value(q, covered);
    EXPECT_NEAR(d[0], 3.0, 0.5) << edge_deg;
    EXPECT_NEAR(d[1], -2.0, 0.5) << edge_deg;
    EXPECT_NEAR(d[2], 0.0, 0.5) << edge_deg;
    EXPECT_NEAR(d[3], 3.0, 0.5) << edge_deg;
  }

  // The GP over the same touches (markers 2 mm apart, to keep it small),
  // its lengthscale chosen for them, gives the hollow point under 1 mm where
  // it lies 3 mm from the face: the inner face it meshes there lies about
  // 2 mm or more into the hollow.
  ImplicitSurfaceOptions options;
  options.kernel = ImplicitKernelKind::matern52;
  ImplicitSurface gp(options);
  for (const ImplicitTouch& touch : thin_wall(2.0).touches) gp.add(touch);
  EXPECT_LT(gp.mean(q.topRows(1))[0], 1.0);
}

// Markers 2 mm apart: a point's 20 nearest reach the touch on the wall's
// other face 4 mm away, and a normal fitted to both faces' points lies
// along the wall; only the points touched from its own side count.
TEST(LocalQuadricSurface, NormalsComeFromPointsTouchedFromTheSameSide) {
  const Touched t = thin_wall(2.0, 30);
  const LocalQuadricSurface surface(t.points, t.outward);
  for (const double deg : {5.0, 10.0, 15.0}) {
    Eigen::MatrixX3d q(3, 3);
    for (int i = 0; i < 3; ++i) q.row(i) = at_radius(36.0 + 2 * i, deg, 45).transpose();
    std::vector<bool> covered;
    const Eigen::VectorXd d = surface.value(q, covered);
    EXPECT_NEAR(d[0], 0.0, 0.1) << deg << " degrees, the inner face";
    EXPECT_NEAR(d[1], -2.0, 0.1) << deg << " degrees, inside the wall";
    EXPECT_NEAR(d[2], 0.0, 0.1) << deg << " degrees, the outer face";
    EXPECT_FALSE(surface.in_free_space(q.row(1).transpose())) << deg << " degrees";
  }
}

// A flat face touched densely as one touch: at(s, y) for s from `from` to
// `to` and y from -15 to 15, 1 mm apart, its palm's normal `out`.
template <class At>
void add_face(Touched& t, At at, double from, double to, const Eigen::Vector3d& out) {
  std::vector<Eigen::Vector3d> ps;
  for (double s = from; s <= to + 1e-9; s += 1.0)
    for (double y = -15; y <= 15 + 1e-9; y += 1.0) ps.push_back(at(s, y));
  ImplicitTouch touch;
  touch.points_mm.resize(static_cast<Eigen::Index>(ps.size()), 3);
  for (std::size_t i = 0; i < ps.size(); ++i) touch.points_mm.row(static_cast<Eigen::Index>(i)) = ps[i].transpose();
  touch.normals = out.transpose().replicate(touch.points_mm.rows(), 1);
  t.add(touch);
}

// A step's profile, touched densely on its three faces: the tall part's
// top z = 40 for x < 5, the riser x = 5 from z = 20 to 40, the low part's
// top z = 20 for x > 5.
Touched step_faces() {
  Touched t;
  add_face(t, [](double x, double y) { return Eigen::Vector3d(x, y, 40); }, -30, 5, {0, 0, 1});
  add_face(t, [](double z, double y) { return Eigen::Vector3d(5, y, z); }, 20, 40, {1, 0, 0});
  add_face(t, [](double x, double y) { return Eigen::Vector3d(x, y, 20); }, 5, 35, {0, 0, 1});
  return t;
}

TEST(LocalQuadricSurface, APlaneIsNotCarriedPastASharpEdge) {
  const Touched t = step_faces();
  Eigen::MatrixX3d q(4, 3);
  q.row(0) << 2, 0, 22;     // inside the tall part, 3 mm behind the riser, 2 mm above the low top's plane
  q.row(1) << 9, 0, 39;     // outside, 4 mm in front of the riser, 1 mm below the tall top's plane
  q.row(2) << -15, 0, 42;   // 2 mm above the tall top, far from its edge
  q.row(3) << 20, 0, 17;    // 3 mm under the low top
  std::vector<bool> covered;
  const Eigen::VectorXd nearest = LocalQuadricSurface(t.points, t.outward).value(q, covered);
  // The nearest patch alone: the low top's plane runs on under the riser,
  // the tall top's past its edge, and each says the wrong side.
  EXPECT_GT(nearest[0], 0.0);
  EXPECT_LT(nearest[1], 0.0);
  LocalQuadricOptions options;
  options.edge_deg = 60;
  const Eigen::VectorXd edges = LocalQuadricSurface(t.points, t.outward, options).value(q, covered);
  EXPECT_NEAR(edges[0], -3.0, 0.3) << "concave edge: inside either face's solid";
  EXPECT_NEAR(edges[1], 4.0, 0.3) << "convex edge: inside both";
  EXPECT_EQ(edges[2], nearest[2]) << "a face far from its edges keeps its own distance";
  EXPECT_EQ(edges[3], nearest[3]);
  EXPECT_NEAR(edges[2], 2.0, 0.1);
  EXPECT_NEAR(edges[3], -3.0, 0.1);
}

TEST(LocalQuadricSurface, FreeSpaceIsWhereAGelLayInFrontOfAPatch) {
  const Touched t = thin_wall();
  const LocalQuadricSurface surface(t.points, t.outward);
  EXPECT_TRUE(surface.in_free_space(at_radius(44.0, 15, 45)));   // 4 mm in front of an outer patch
  EXPECT_TRUE(surface.in_free_space(at_radius(30.0, 60, 45)));   // 6 mm in front of an inner patch
  EXPECT_FALSE(surface.in_free_space(at_radius(38.0, 15, 45)));  // inside the wall
  EXPECT_FALSE(surface.in_free_space(at_radius(30.0, 30, 45)));  // the hollow where no gel lay
  EXPECT_FALSE(surface.in_free_space(at_radius(40.5, 15, 45)));  // within the margin of the face
}

// A gel pressed into a concave corner: a floor z = 0 touched from above for
// x from 0 to 30, a wall x = 0 touched from the side for z from 0 to 30
// (y from -15 to 15). The floor lies in front of the wall's lowest patches,
// and the wall in front of the floor's patches by it.
TEST(LocalQuadricSurface, AConcaveCornersTouchedFacesAreNotEachOthersFreeSpace) {
  Touched t;
  add_face(t, [](double x, double y) { return Eigen::Vector3d(x, y, 0); }, 0, 30, {0, 0, 1});
  add_face(t, [](double z, double y) { return Eigen::Vector3d(0, y, z); }, 0, 30, {1, 0, 0});
  const Eigen::Vector3d on_floor(3, 0, 0), on_wall(0, 0, 3), in_the_air(4, 0, 4);
  const LocalQuadricSurface cylinders(t.points, t.outward);
  EXPECT_TRUE(cylinders.in_free_space(on_floor)) << "in front of the wall's lowest patch";
  EXPECT_TRUE(cylinders.in_free_space(on_wall)) << "in front of the floor's patch by the wall";
  LocalQuadricOptions options;
  options.free_support_mm = 3.5;
  const LocalQuadricSurface supported(t.points, t.outward, options);
  EXPECT_FALSE(supported.in_free_space(on_floor));
  EXPECT_FALSE(supported.in_free_space(on_wall));
  EXPECT_TRUE(supported.in_free_space(in_the_air));
}

TEST(LocalQuadricSurface, TheSameValuesOnAnyNumberOfThreads) {
  const Touched t = thin_wall();
  const LocalQuadricSurface surface(t.points, t.outward);
  Eigen::MatrixX3d q(2000, 3);
  for (Eigen::Index i = 0; i < q.rows(); ++i) q.row(i) = at_radius(30.0 + 0.007 * i, 0.17 * i, 20 + 0.02 * i).transpose();
  std::vector<bool> one, two;
  const Eigen::VectorXd a = surface.value(q, one, 1), b = surface.value(q, two, 2);
  EXPECT_EQ(one, two);
  EXPECT_TRUE(a.cwiseEqual(b).all());
}

TEST(LocalQuadricSurface, SaysNothingWhereNoPatchReaches) {
  const Touched t = thin_wall();
  const LocalQuadricSurface surface(t.points, t.outward);
  Eigen::MatrixX3d q(1, 3);
  q.row(0) << 0, 0, 45;  // the cup's axis: 36 mm from every patch
  std::vector<bool> covered;
  surface.value(q, covered);
  EXPECT_FALSE(covered[0]);
}

TEST(LocalQuadricSurface, RefusesBadInputSayingWhat) {
  const Touched t = thin_wall();
  EXPECT_THROW(LocalQuadricSurface(Eigen::MatrixX3d(0, 3), Eigen::MatrixX3d(0, 3)), InputError);
  EXPECT_THROW(LocalQuadricSurface(t.points, t.outward.topRows(3)), InputError);
  Eigen::MatrixX3d bad = t.points;
  bad(7, 1) = std::nan("");
  EXPECT_THROW(LocalQuadricSurface(bad, t.outward), InputError);
  LocalQuadricOptions options;
  options.edge_deg = 180;
  EXPECT_THROW(LocalQuadricSurface(t.points, t.outward, options), InputError);
  options.edge_deg = 0;
  options.free_support_mm = -1;
  EXPECT_THROW(LocalQuadricSurface(t.points, t.outward, options), InputError);
  options.free_support_mm = 0;
  options.reach_mm = 0;
  try {
    LocalQuadricSurface(t.points, t.outward, options);
    FAIL() << "reach_mm 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reach_mm"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace touchcloud::gp
