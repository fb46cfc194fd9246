// Snell's law in vector form, checked against the scalar law.
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "touchcloud/optics/snell.hpp"

namespace touchcloud::optics {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Vector3d at_angle(double theta, const Eigen::Vector3d& normal, const Eigen::Vector3d& tangent) {
  return std::cos(theta) * normal + std::sin(theta) * tangent;
}

TEST(Snell, ObeysTheScalarLawInThePlaneOfIncidence) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.1, -0.2, 1.0).normalized();
  const Eigen::Vector3d tangent = n.unitOrthogonal();
  for (double degrees : {0.0, 1e-6, 10.0, 30.0, 60.0, 89.9}) {
    const double theta = degrees * kPi / 180;
    const Refraction out = refract(at_angle(theta, n, tangent), n, 1.0, 1.49);
    ASSERT_EQ(out.status, TraceStatus::Ok);
    EXPECT_NEAR(out.direction.norm(), 1.0, 1e-15);
    const double expected = std::asin(std::sin(theta) / 1.49);
    EXPECT_NEAR(out.direction.dot(tangent), std::sin(expected), 1e-15) << degrees;
    EXPECT_NEAR(out.direction.dot(n), std::cos(expected), 1e-15) << degrees;
    EXPECT_NEAR(out.direction.dot(n.cross(tangent)), 0.0, 1e-15);  // stays in the plane
  }
}

TEST(Snell, RefractingBackRestoresTheRay) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d d = Eigen::Vector3d(0.4, 0.3, 0.8).normalized();
  const Refraction into = refract(d, n, 1.49, 1.41);
  ASSERT_EQ(into.status, TraceStatus::Ok);
  // Reversed light path: -t from 1.41 into 1.49 across -n gives -d.
  const Refraction back = refract(-into.direction, -n, 1.41, 1.49);
  ASSERT_EQ(back.status, TraceStatus::Ok);
  EXPECT_NEAR((back.direction + d).norm(), 0.0, 1e-15);
}

TEST(Snell, TotalInternalReflectionIsAStatusNotNaN) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();
  const double critical = std::asin(1.0 / 1.6);
  const Refraction beyond = refract(at_angle(critical + 1e-9, n, tangent), n, 1.6, 1.0);
  EXPECT_EQ(beyond.status, TraceStatus::TotalInternalReflection);
  EXPECT_TRUE(beyond.direction.allFinite());
  EXPECT_EQ(refract(at_angle(1.2, n, tangent), n, 1.6, 1.0).status, TraceStatus::TotalInternalReflection);

  const Refraction below = refract(at_angle(critical - 1e-9, n, tangent), n, 1.6, 1.0);
  ASSERT_EQ(below.status, TraceStatus::Ok);
  EXPECT_GT(below.direction.dot(tangent), 0.9999);  // leaves nearly along the face
  EXPECT_TRUE(below.direction.allFinite());
}

TEST(Snell, ARayNotHeadingIntoTheInterfaceMissesIt) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  EXPECT_EQ(refract(Eigen::Vector3d::UnitX(), n, 1.0, 1.5).status, TraceStatus::MissesPlate);
  EXPECT_EQ(refract(-n, n, 1.0, 1.5).status, TraceStatus::MissesPlate);
}

}  // namespace
}  // namespace touchcloud::optics
