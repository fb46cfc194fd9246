// Touches from any side (touchcloud/planning/side_choice.hpp) on a model
// whose answers are known: a sphere's signed distance whose variance grows
// towards +x. The candidates face out of the sphere, the best is where the
// variance gathers, a footprint sums its neighbours, and a start turns
// evenly round the vertical.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "touchcloud/error.hpp"
#include "touchcloud/planning/side_choice.hpp"

using namespace touchcloud;

namespace {

class UncertainSphere : public ImplicitModel {
 public:
  Eigen::VectorXd mean(const Eigen::MatrixX3d& p) const override {
    return p.rowwise().norm().array() - kRadiusMm;
  }
  Eigen::VectorXd variance(const Eigen::MatrixX3d& p) const override {
    return (p.col(0).array() + kRadiusMm).square() / 100.0;  // 0 at x = -R, 4 mm^2 at x = R
  }
  static constexpr double kRadiusMm = 20.0;
};

// Points on the sphere (Fibonacci lattice).
std::vector<Eigen::Vector3d> sphere_points(int count) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < count; ++i) {
    const double z = 1 - (2.0 * i + 1) / count, rho = std::sqrt(1 - z * z), phi = i * std::numbers::pi * (3 - std::sqrt(5.0));
    out.push_back(UncertainSphere::kRadiusMm * Eigen::Vector3d(rho * std::cos(phi), rho * std::sin(phi), z));
  }
  return out;
}

}  // namespace

TEST(SideChoice, CandidatesFaceOutAndTheBestIsWhereTheVarianceGathers) {
  const UncertainSphere model;
  const auto candidates = planning::side_candidates(model, sphere_points(2000), {}, 7);
  ASSERT_EQ(candidates.size(), 150u);
  for (const auto& c : candidates) {
    EXPECT_NEAR(c.outward.norm(), 1.0, 1e-12);
    EXPECT_GT(c.outward.dot(c.point_mm.normalized()), 0.999) << c.point_mm.transpose();  // the radial direction
    EXPECT_NEAR(c.variance_mm2, std::pow(c.point_mm.x() + UncertainSphere::kRadiusMm, 2) / 100.0, 1e-12);
    EXPECT_GE(c.footprint_variance_mm2, c.variance_mm2);  // its own point is inside its footprint
  }
  for (std::size_t i = 1; i < candidates.size(); ++i)
    EXPECT_GE(candidates[i - 1].footprint_variance_mm2, candidates[i].footprint_variance_mm2);
  EXPECT_GT(candidates.front().point_mm.x(), 0.5 * UncertainSphere::kRadiusMm);  // on the uncertain side
  EXPECT_LT(candidates.back().point_mm.x(), -0.5 * UncertainSphere::kRadiusMm);
}

TEST(SideChoice, AFootprintIsTheVarianceWithinItsRadiusAndDepth) {
  const UncertainSphere model;
  planning::SideChoiceOptions o;
  o.footprint_radius_mm = 0.001;  // a footprint holding its own point alone
  for (const auto& c : planning::side_candidates(model, sphere_points(500), o, 3))
    EXPECT_DOUBLE_EQ(c.footprint_variance_mm2, c.variance_mm2);
}

TEST(SideChoice, TheSameSeedDrawsTheSameCandidatesAndNoSurfaceIsAnError) {
  const UncertainSphere model;
  const auto a = planning::side_candidates(model, sphere_points(800), {}, 11);
  const auto b = planning::side_candidates(model, sphere_points(800), {}, 11);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].point_mm, b[i].point_mm);
  EXPECT_THROW(planning::side_candidates(model, {}, {}, 1), InputError);
}

TEST(SideChoice, AStartGoesStraightDownThenEvenlyRoundTheVertical) {
  const auto d = planning::start_directions(5, 45.0);
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(d[0], Eigen::Vector3d(0, 0, -1));
  for (std::size_t k = 1; k < d.size(); ++k) {
    EXPECT_NEAR(d[k].norm(), 1.0, 1e-12);
    EXPECT_NEAR(std::acos(-d[k].z()) * 180.0 / std::numbers::pi, 45.0, 1e-9);
  }
  EXPECT_NEAR((d[1] + d[2] + d[3] + d[4]).head<2>().norm(), 0.0, 1e-12);  // evenly round
}

TEST(SideChoice, ObliquePressesTurnFromTheNormalTowardsStraightDown) {
  // A cup's inner wall facing -x: pressed along +x, then turned towards down.
  const auto d = planning::press_directions({-1, 0, 0}, {30, 90, 120});
  ASSERT_EQ(d.size(), 4u);
  EXPECT_NEAR((d[0] - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(std::acos(d[1].dot(d[0])) * 180 / std::numbers::pi, 30.0, 1e-9);
  EXPECT_NEAR(d[1].y(), 0.0, 1e-12);  // in the plane of the normal and the vertical
  EXPECT_LT(d[1].z(), 0.0);           // heading down
  EXPECT_NEAR((d[2] - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((d[3] - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, 1e-12);  // no further than straight down
  for (const auto& v : d) EXPECT_NEAR(v.norm(), 1.0, 1e-12);
  // Straight down already, or straight up: nothing to turn.
  EXPECT_EQ(planning::press_directions({0, 0, 1}, {30}).size(), 1u);
  EXPECT_EQ(planning::press_directions({0, 0, -1}, {30}).size(), 1u);
  EXPECT_EQ(planning::press_directions({0, 1, 0}, {}).size(), 1u);
}
