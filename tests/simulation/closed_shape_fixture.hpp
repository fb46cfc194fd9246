// Closed shapes for touches from any side: a sphere and a torus as fine
// OBJ meshes (their facets lie within 0.01 mm of the analytic surfaces),
// scenes that place them, and a touch pressed to its end.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "sim_fixture.hpp"
#include "touchcloud/simulation/objects/approach_view.hpp"

namespace touchcloud::test {

// Facets per turn: the sagitta R (1 - cos(pi / n)) stays under 0.01 mm for
// the shapes below (30 mm sphere: 0.009 mm at 128 rows; torus: 0.004 + 0.005).
inline constexpr int kTurnFacets = 256;

// The surface of revolution of `profile(t)` = (radius, z) for t in [0, 1],
// about z; `closed_loop` joins t = 1 back to t = 0 (a torus' tube).
template <class Profile>
std::string revolution_obj(Profile profile, int rows, bool closed_loop) {
  std::ostringstream s;
  s.precision(17);
  const int ring = kTurnFacets;
  const int points = closed_loop ? rows : rows + 1;
  for (int i = 0; i < points; ++i) {
    const Eigen::Vector2d rz = profile(static_cast<double>(i) / rows);
    for (int j = 0; j < ring; ++j) {
      const double a = 2 * M_PI * j / ring;
      s << "v " << rz.x() * std::cos(a) << " " << rz.x() * std::sin(a) << " " << rz.y() << "\n";
    }
  }
  const int bands = closed_loop ? rows : rows;
  for (int i = 0; i < bands; ++i)
    for (int j = 0; j < ring; ++j) {
      const int i1 = closed_loop ? (i + 1) % rows : i + 1;
      const int a = i * ring + j + 1, b = i * ring + (j + 1) % ring + 1;
      const int c = i1 * ring + (j + 1) % ring + 1, d = i1 * ring + j + 1;
      s << "f " << a << " " << b << " " << c << "\nf " << a << " " << c << " " << d << "\n";
    }
  return s.str();
}

// A sphere of radius `r` centred at the origin (poles as rings of one point).
inline std::string sphere_obj(double r) {
  return revolution_obj([r](double t) { return Eigen::Vector2d(r * std::sin(M_PI * t), -r * std::cos(M_PI * t)); },
                        128, false);
}

// A torus about z: ring radius `big`, tube radius `small`, centred at the origin.
inline std::string torus_obj(double big, double small) {
  return revolution_obj(
      [=](double t) {
        const double a = 2 * M_PI * t;
        return Eigen::Vector2d(big + small * std::cos(a), small * std::sin(a));
      },
      128, true);
}

// A scene with the mesh `obj` centred at `centre_mm`, the default marker
// GelStereo, the ideal sensor's truth (contact), the scene's other lines.
inline simulation::Scene closed_scene(const TempDir& dir, const std::string& obj, const Eigen::Vector3d& centre_mm,
                                      const std::string& extra = "") {
  write_file(dir / "shape.obj", obj);
  std::ostringstream s;
  s << "object: {mesh: shape.obj, pose: {xyz_mm: [" << centre_mm.x() << ", " << centre_mm.y() << ", " << centre_mm.z()
    << "]}}\nrobot: {speed_mm_s: 6, approach_speed_mm_s: 30, press_depth_mm: 1.5, safe_clearance_mm: 2}\n"
    << "effects: [contact]\n" << extra;
  write_file(dir / "scene.yaml", s.str());
  return simulation::load_scene(dir / "scene.yaml");
}

// One touch at `target` as marker_gelstereo_simulator runs it with
// stable_contact standing in (stable once 3.9 mm past first contact); the
// pressed frame.
inline const simulation::TouchFrame& press_touch(simulation::TouchSimulation& sim, const simulation::PressTarget& target) {
  bool stable = false;
  for (int i = 0; i < 10000; ++i) {
    const simulation::TouchFrame& f = sim.step(target, stable);
    if (f.touch.pressed) return f;
    stable = f.travel_past_contact_mm >= 3.9;
  }
  throw std::runtime_error("press_touch: the touch never ended");
}

}  // namespace touchcloud::test
