#include "sim_fixture.hpp"

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

namespace touchcloud::test {

std::filesystem::path write_plane_scene(const TempDir& dir, const std::string& effects, const std::string& extra,
                                        const std::string& name) {
  const auto file = dir / name;
  write_file(file, "object: {analytic: plane, height_mm: " + std::to_string(kPlaneHeightMm) + "}\n" + extra +
                       "\neffects: " + effects + "\n");
  return file;
}

touch_simulator::Scene plane_scene(const TempDir& dir, const std::string& effects, const std::string& extra) {
  return touch_simulator::load_scene(write_plane_scene(dir, effects, extra));
}

const touch_simulator::SimulatedFrame& press_into(touch_simulator::TouchSimulation& sim, const Eigen::Vector2d& xy, double travel_mm) {
  for (int i = 0; i < 10000; ++i) {
    const auto& f = sim.step(xy, false);
    if (f.travel_past_contact_mm >= travel_mm) return f;
  }
  throw std::runtime_error("press_into: never got that deep");
}

std::string ring_obj(double unit) {
  constexpr int n = 64;
  const double outer = 40 * unit, inner = 20 * unit, height = 50 * unit;
  std::ostringstream obj;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, c = std::cos(a), s = std::sin(a);
    obj << "v " << outer * c << ' ' << outer * s << ' ' << height << '\n'   // 4i + 1
        << "v " << inner * c << ' ' << inner * s << ' ' << height << '\n'   // 4i + 2
        << "v " << outer * c << ' ' << outer * s << " 0\n"                  // 4i + 3
        << "v " << inner * c << ' ' << inner * s << " 0\n";                 // 4i + 4
  }
  for (int i = 0; i < n; ++i) {
    const int a = 4 * i + 1, b = 4 * ((i + 1) % n) + 1;
    obj << "f " << a << ' ' << b << ' ' << b + 1 << ' ' << a + 1 << '\n'          // top
        << "f " << a + 1 << ' ' << b + 1 << ' ' << b + 3 << ' ' << a + 3 << '\n'  // inner wall
        << "f " << a << ' ' << a + 2 << ' ' << b + 2 << ' ' << b << '\n';         // outer wall
  }
  return obj.str();
}

}  // namespace touchcloud::test
