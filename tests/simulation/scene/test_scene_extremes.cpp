// Extreme scene values are refused in the scene file, where they are given,
// not later in another stage as "not finite" (or a run with 0 touches).
#include <gtest/gtest.h>

#include "sim_fixture.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

TEST(SceneExtremes, HugeAndTinyValuesAreNamedWhereTheyAreGiven) {
  TempDir dir;
  for (const auto& [extra, message] : std::vector<std::pair<std::string, std::string>>{
           {"sensor: {fps: 1e308}", "sensor.fps: 1e+308 is out of range (at most 1e+06 in magnitude)"},
           {"sensor: {fps: 5000}", "sensor.fps: 5000 frames per second is more than a camera gives (at most 1000)"},
           {"robot: {speed_mm_s: 1e300}", "robot.speed_mm_s: 1e+300 is out of range"},
           {"sensor: {markers: {min_spacing_mm: 1e-300, mean_spacing_mm: 1e-301}}",
            "sensor.markers.mean_spacing_mm: must be >= min_spacing_mm (1e-300)"},
       }) {
    const std::string m = input_error([&] { plane_scene(dir, "[]", extra); });
    EXPECT_NE(m.find(message), std::string::npos) << extra << " -> " << m;
  }
}
