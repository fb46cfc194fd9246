#include "sim_fixture.hpp"

#include <cmath>
#include <map>
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

simulation::Scene plane_scene(const TempDir& dir, const std::string& effects, const std::string& extra) {
  return simulation::load_scene(write_plane_scene(dir, effects, extra));
}

const simulation::TouchFrame& press_into(simulation::GelStereoSimulation& sim, const Eigen::Vector2d& xy, double travel_mm) {
  for (int i = 0; i < 10000; ++i) {
    const auto& f = sim.step(xy, false);
    if (f.travel_past_contact_mm >= travel_mm) return f;
  }
  throw std::runtime_error("press_into: never got that deep");
}

void expect_refuses_other_sensors(const std::string& plugin) {
  const std::map<std::string, std::string> sensor_of_plugin{
      {"marker_gelstereo_simulator", "sensor: {pattern: markers}"},
      {"colour_gelstereo_simulator", "sensor: {pattern: colour_pattern}"},
      {"gelsight_simulator", "sensor: {family: gelsight}"}};
  ASSERT_EQ(sensor_of_plugin.count(plugin), 1u) << plugin;
  TempDir dir;
  PluginRegistry registry = test_registry();
  for (const auto& [other, sensor] : sensor_of_plugin) {
    if (other == plugin) continue;
    const auto scene = write_plane_scene(dir, "[contact, render]", sensor, other + ".yaml");
    write_file(dir / "p.yaml", "stages:\n  - id: sim\n    plugin: " + plugin + "\n    params: {scene: " +
                                   scene.string() + ", target_xy_mm: [0, 0]}\n");
    try {
      Pipeline::load(dir / "p.yaml", {}, registry);
      ADD_FAILURE() << plugin << " took a scene of " << other << "'s sensor";
    } catch (const InputError& e) {
      ASSERT_FALSE(e.diagnostics().empty()) << e.what();
      const Diagnostic& d = e.diagnostics().front();
      EXPECT_NE(d.message.find("parameter 'scene'"), std::string::npos) << d.str();
      EXPECT_NE(d.message.find("use plugin " + other), std::string::npos) << d.str();
      EXPECT_EQ(d.where.line, 4) << d.str();  // the line of `params:`, where `scene` is set
    }
  }
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
