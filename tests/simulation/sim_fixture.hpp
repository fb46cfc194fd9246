// Scenes written on the fly for the simulator's tests: a flat object (a plane
// 10 mm above the table) under the default sensor, with chosen effects.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"

namespace touchcloud::test {

inline constexpr double kPlaneHeightMm = 10.0;
// That plane as a scene's `object:` value.
inline const std::string kPlaneObject = "{analytic: plane, height_mm: 10}";

// A scene file: the plane, then `extra` YAML lines (top-level), with `effects`
// as the effects list, e.g. "[contact, refraction]".
std::filesystem::path write_plane_scene(const TempDir& dir, const std::string& effects, const std::string& extra = "",
                                        const std::string& name = "scene.yaml");
simulation::Scene plane_scene(const TempDir& dir, const std::string& effects, const std::string& extra = "");

// A ring 50 mm tall (outer radius 40 mm, inner 20 mm, vertices times
// `unit_mm`, e.g. 0.001 for a mesh in metres) as an OBJ: top annulus, inner
// and outer walls. The gel (radius 32.5 mm) cannot reach the table in its
// hole: the dome rests on the inner rim.
std::string ring_obj(double unit = 1.0);

// Steps a touch at `xy` without a stable-contact verdict until the sensor is
// `travel_mm` past first contact; returns the last frame.
const simulation::TouchFrame& press_into(simulation::GelStereoSimulation& sim, const Eigen::Vector2d& xy, double travel_mm);

// Checks that `touchcloud validate` refuses a pipeline whose stage of plugin
// `plugin` (one of the simulator stages) reads a plane scene of another
// stage's sensor, at the stage's `scene` parameter and naming the plugin to
// use instead, for both other sensors.
void expect_refuses_other_sensors(const std::string& plugin);

// The InputError message `f` throws, or "" (with a test failure) when it does not.
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

}  // namespace touchcloud::test
