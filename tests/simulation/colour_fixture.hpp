// Scenes of the colour-pattern GelStereo for tests: the default sensor with
// `pattern: colour_pattern`, rectified images at a test-friendly size, and
// objects to press (the plane, a tilted plane, a sphere) as OBJ meshes.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include "test_support.hpp"
#include "touchcloud/simulation/gelstereo_simulation.hpp"

namespace touchcloud::test {

// 640 x 360 rectified images (a quarter of the camera's pixels); 1 mm blobs
// are about 4 px across there.
inline constexpr const char* kColourSensor =
    "sensor:\n"
    "  pattern: colour_pattern\n"
    "  colour_pattern: {feature_mm: 1.0, image_size_px: [640, 360], vignetting: 0.1}\n";

// A quad of +-80 mm turned by `tilt_deg` about the y axis through (0, 0, height).
inline std::string tilted_plane_obj(double tilt_deg, double height_mm) {
  const double c = std::cos(tilt_deg * M_PI / 180), s = std::sin(tilt_deg * M_PI / 180), h = 80;
  std::ostringstream obj;
  for (double y : {-h, h})
    for (double x : {-h, h}) obj << "v " << c * x << ' ' << y << ' ' << height_mm - s * x << '\n';
  obj << "f 1 2 4 3\n";
  return obj.str();
}

// A UV sphere of `radius_mm` centred at (0, 0, centre_z_mm).
inline std::string sphere_obj(double radius_mm, double centre_z_mm, int rings = 48, int segments = 96) {
  std::ostringstream obj;
  obj << "v 0 0 " << centre_z_mm + radius_mm << '\n';
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      obj << "v " << radius_mm * std::sin(theta) * std::cos(phi) << ' ' << radius_mm * std::sin(theta) * std::sin(phi)
          << ' ' << centre_z_mm + radius_mm * std::cos(theta) << '\n';
    }
  }
  obj << "v 0 0 " << centre_z_mm - radius_mm << '\n';
  auto v = [&](int ring, int seg) { return 2 + (ring - 1) * segments + seg % segments; };
  const int bottom = 2 + (rings - 1) * segments;
  for (int j = 0; j < segments; ++j) obj << "f 1 " << v(1, j) << ' ' << v(1, j + 1) << '\n';
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j)
      obj << "f " << v(i, j) << ' ' << v(i + 1, j) << ' ' << v(i + 1, j + 1) << ' ' << v(i, j + 1) << '\n';
  for (int j = 0; j < segments; ++j) obj << "f " << v(rings - 1, j) << ' ' << bottom << ' ' << v(rings - 1, j + 1) << '\n';
  return obj.str();
}

// A colour-pattern scene: `object` (a YAML mapping), `effects`, and lines
// appended to the sensor's colour_pattern mapping replaced by `sensor`.
inline simulation::Scene colour_scene(const TempDir& dir, const std::string& object, const std::string& effects,
                                           const std::string& sensor = kColourSensor,
                                           const std::string& name = "colour.yaml") {
  const auto file = dir / name;
  write_file(file, "object: " + object + "\n" + sensor + "effects: " + effects + "\n");
  return simulation::load_scene(file);
}

}  // namespace touchcloud::test
