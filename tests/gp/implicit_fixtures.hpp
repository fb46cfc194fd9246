// Touch patches on a sphere and a torus from known poses, as the sensor
// gives them: the contact points of a palm pressed along -n (base frame, mm)
// and, for every point, the palm's normal n.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "touchcloud/gp/implicit_surface.hpp"

namespace touchcloud::test {

// Points within `radius_mm` of the contact on a square lattice of `step_mm`:
// (s, t) offsets along two tangents of n.
inline std::vector<Eigen::Vector2d> footprint(double radius_mm = 5.0, double step_mm = 2.5) {
  std::vector<Eigen::Vector2d> st;
  for (double s = -radius_mm; s <= radius_mm + 1e-9; s += step_mm)
    for (double t = -radius_mm; t <= radius_mm + 1e-9; t += step_mm)
      if (s * s + t * t <= radius_mm * radius_mm + 1e-9) st.emplace_back(s, t);
  return st;
}

inline gp::ImplicitTouch touch_with_palm_normal(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n) {
  gp::ImplicitTouch t;
  t.points_mm.resize(static_cast<Eigen::Index>(points.size()), 3);
  t.normals.resize(t.points_mm.rows(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    t.points_mm.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
    t.normals.row(static_cast<Eigen::Index>(i)) = n.normalized().transpose();
  }
  return t;
}

struct SphereObject {
  Eigen::Vector3d centre_mm{5, -3, 40};
  double radius_mm = 20;

  // A touch whose palm approaches along -n (n outward, unit).
  gp::ImplicitTouch touch(const Eigen::Vector3d& n) const {
    const Eigen::Vector3d a = n.unitOrthogonal(), b = n.cross(a);
    std::vector<Eigen::Vector3d> points;
    for (const Eigen::Vector2d& st : footprint())
      points.push_back(centre_mm + radius_mm * (radius_mm * n + st[0] * a + st[1] * b).normalized());
    return touch_with_palm_normal(points, n);
  }
  // `count` approach directions spread evenly over the sphere (Fibonacci lattice).
  std::vector<gp::ImplicitTouch> touches(int count) const {
    std::vector<gp::ImplicitTouch> out;
    for (int i = 0; i < count; ++i) {
      const double z = 1 - (2.0 * i + 1) / count, rho = std::sqrt(1 - z * z);
      const double phi = i * std::numbers::pi * (3 - std::sqrt(5.0));
      out.push_back(touch({rho * std::cos(phi), rho * std::sin(phi), z}));
    }
    return out;
  }
};

struct TorusObject {
  double major_mm = 25, minor_mm = 8;  // about the z axis, centred at the origin

  Eigen::Vector3d point(double u, double v) const {
    return {(major_mm + minor_mm * std::cos(v)) * std::cos(u), (major_mm + minor_mm * std::cos(v)) * std::sin(u),
            minor_mm * std::sin(v)};
  }
  Eigen::Vector3d normal(double u, double v) const {
    return {std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v)};
  }
  gp::ImplicitTouch touch(double u, double v) const {
    std::vector<Eigen::Vector3d> points;
    for (const Eigen::Vector2d& st : footprint())
      points.push_back(point(u + st[0] / (major_mm + minor_mm * std::cos(v)), v + st[1] / minor_mm));
    return touch_with_palm_normal(points, normal(u, v));
  }
  // `around` x `across` touches: around the ring, and around the tube
  // (the inner side of the ring included).
  std::vector<gp::ImplicitTouch> touches(int around, int across) const {
    std::vector<gp::ImplicitTouch> out;
    for (int i = 0; i < around; ++i)
      for (int j = 0; j < across; ++j)
        out.push_back(touch(2 * std::numbers::pi * (i + 0.5 * (j % 2)) / around, 2 * std::numbers::pi * j / across));
    return out;
  }
};

// A cup's wall about the z axis between radii 36 and 40 mm (a mug's): palm
// patches 6 mm in radius, markers `step_mm` apart, on the outer face every
// `outer_deg` degrees at `heights` (mm), and on the inner face, pressed from
// the hollow, every 60 degrees at 45 mm only.
struct CupWall {
  double inner_mm = 36, outer_mm = 40;

  gp::ImplicitTouch touch(double deg, double z_mm, bool inner, double step_mm) const {
    const double r = inner ? inner_mm : outer_mm, a = deg * std::numbers::pi / 180;
    std::vector<Eigen::Vector3d> points;
    for (const Eigen::Vector2d& st : footprint(6.0, step_mm))
      points.emplace_back(r * std::cos(a + st[0] / r), r * std::sin(a + st[0] / r), z_mm + st[1]);
    const Eigen::Vector3d radial(std::cos(a), std::sin(a), 0);
    return touch_with_palm_normal(points, inner ? Eigen::Vector3d(-radial) : radial);
  }
  std::vector<gp::ImplicitTouch> touches(double step_mm, double outer_deg = 15,
                                         const std::vector<double>& heights = {25, 45, 65}) const {
    std::vector<gp::ImplicitTouch> out;
    for (double deg = 0; deg < 360; deg += outer_deg)
      for (double z : heights) out.push_back(touch(deg, z, false, step_mm));
    for (double deg = 0; deg < 360; deg += 60) out.push_back(touch(deg, 45.0, true, step_mm));
    return out;
  }
  static Eigen::Vector3d at(double r_mm, double deg, double z_mm) {
    const double a = deg * std::numbers::pi / 180;
    return {r_mm * std::cos(a), r_mm * std::sin(a), z_mm};
  }
};

// The cup's touches (outer faces every 15 degrees) and, last, a press from
// above on a floor at z = 10 mm, through the cup's mouth (a 6 mm patch at the axis).
inline std::vector<gp::ImplicitTouch> cup_and_floor_press(double step_mm) {
  std::vector<gp::ImplicitTouch> touches = CupWall().touches(step_mm);
  std::vector<Eigen::Vector3d> floor;
  for (const Eigen::Vector2d& st : footprint(6.0, step_mm)) floor.emplace_back(st[0], st[1], 10.0);
  touches.push_back(touch_with_palm_normal(floor, Eigen::Vector3d::UnitZ()));
  return touches;
}

inline Eigen::MatrixX3d one_row(const Eigen::Vector3d& p) { return p.transpose(); }

// Where a model's mean crosses 0 between a (negative) and b (positive), by
// bisection; Model: gp::ImplicitSurface or gp::SparseImplicitSurface.
template <class Model>
Eigen::Vector3d zero_crossing(const Model& s, Eigen::Vector3d a, Eigen::Vector3d b) {
  EXPECT_LT(s.mean(one_row(a))[0], 0);
  EXPECT_GT(s.mean(one_row(b))[0], 0);
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector3d m = 0.5 * (a + b);
    (s.mean(one_row(m))[0] < 0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

// The largest error of the sphere's radius along 26 rays from its centre.
template <class Model>
double worst_radius_error(const Model& s, const SphereObject& sphere) {
  double worst = 0;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        if (!i && !j && !k) continue;
        const Eigen::Vector3d d = Eigen::Vector3d(i, j, k).normalized();
        const Eigen::Vector3d p = zero_crossing(s, sphere.centre_mm, sphere.centre_mm + 2 * sphere.radius_mm * d);
        worst = std::max(worst, std::abs((p - sphere.centre_mm).norm() - sphere.radius_mm));
      }
  return worst;
}

}  // namespace touchcloud::test
