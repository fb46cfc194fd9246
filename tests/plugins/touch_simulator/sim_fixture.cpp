#include "sim_fixture.hpp"

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

}  // namespace touchcloud::test
