// Scenes of the monocular GelSight-type sensor for tests: the default sensor
// (GelSight Mini-like, 320 x 240 px) with chosen objects and effects, and
// presses of the shipped calibration ball.
#pragma once

#include <string>

#include "touchcloud/simulation/gelsight_simulation.hpp"
#include "test_support.hpp"

namespace touchcloud::test {

// A GelSight scene: `object` (a YAML mapping), `effects`, `sensor` lines
// added to the sensor section (indented by two spaces) and `robot` lines.
inline simulation::Scene gelsight_scene(const TempDir& dir, const std::string& object, const std::string& effects,
                                             const std::string& sensor = "", const std::string& name = "gelsight.yaml") {
  const auto file = dir / name;
  write_file(file, "object: " + object + "\nsensor:\n  family: gelsight\n" + sensor +
                       "robot: {speed_mm_s: 2, press_depth_mm: 0.5}\neffects: " + effects +
                       "\n");
  return simulation::load_scene(file);
}

// The shipped ball scene (sample_clouds/gelsight_ball/scene.yaml).
inline simulation::Scene ball_scene() {
  return simulation::load_scene(source_dir() / "sample_clouds/gelsight_ball/scene.yaml");
}

// The shipped ball scene with other `effects` (a YAML list), written into `dir`.
inline simulation::Scene ball_scene_with(const TempDir& dir, const std::string& effects,
                                         const std::string& name = "ball.yaml") {
  const auto ball = source_dir() / "sample_clouds/gelsight_ball";
  std::string text = read_file(ball / "scene.yaml");
  text = text.substr(0, text.find("\neffects:") + 1) + "effects: " + effects + "\n";
  const std::string mesh = "mesh: ball_cap.ply";
  text.replace(text.find(mesh), mesh.size(), "mesh: " + (ball / "ball_cap.ply").string());
  write_file(dir / name, text);
  return simulation::load_scene(dir / name);
}

// Steps a touch at `xy` without a stable-contact verdict until the pad is
// `travel_mm` past first contact.
inline const simulation::TouchFrame& press_pad_into(simulation::GelSightSimulation& sim,
                                                            const Eigen::Vector2d& xy, double travel_mm) {
  for (int i = 0; i < 100000; ++i) {
    const auto& f = sim.step(xy, false);
    if (f.travel_past_contact_mm >= travel_mm) return f;
  }
  throw std::runtime_error("press_pad_into: never got that deep");
}

}  // namespace touchcloud::test
