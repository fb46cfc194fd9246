// A monocular GelSight-type sensor (the ContactNet/TactileDepthNet report's) as a `sensor:` section gives it,
// with `family: gelsight`: a flat gel pad of some thickness on a clear plate,
// lit by coloured LEDs from several sides and seen by one camera from behind.
// GelSight Mini-like defaults: 240 x 320 px at 0.06 mm/px (a 14.4 x 19.2 mm
// pad), three lights (red, green, blue) 120 degrees apart.
//
// Frames. The sensor frame {S} has its origin on the plate's gel-side face at
// the image centre, x along the image's columns (u), y along its rows (v), z
// along the camera's axis into the gel; the gel's outer face is z =
// thickness_mm at rest. Pixel (u, v) sees the gel at
// x = (u - (width - 1) / 2) mm_per_px, y = (v - (height - 1) / 2) mm_per_px
// (the camera is telecentric over the small pad).
//
// Photometric model. A height map H (mm, the gel pushed towards the camera,
// >= 0) has the normal n = (-dH/dx, -dH/dy, 1) / |.| in the frame whose x, y
// are the image's and whose z points towards the camera; light directions
// are given in that frame (z > 0: on the camera's side of the gel). Each
// light k adds colour_k (diffuse max(0, n.l_k) + specular max(0, r_k.z)^shininess)
// (r_k: l_k mirrored about n); the image is the no-contact background plus
// the shading of n minus the shading of the flat gel's normal, so a flat gel
// renders the background exactly.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::sensor {

// Which kind of sensor a `sensor:` section describes (its `family` field;
// absent: gelstereo, so every older file reads unchanged).
enum class SensorFamily { GelStereo, GelSight };
const char* to_string(SensorFamily family);

// The most frames per second a scene may ask of either family's camera.
inline constexpr double kMaxSensorFps = 1000;

struct PhotometricLight {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit, towards the light (see above)
  Eigen::Vector3d colour_rgb = Eigen::Vector3d::Zero();  // grey levels per channel at n = l
};

struct GelSightSensor {
  std::string name = "gelsight_mini";  // calibrations name the sensor they belong to
  int width_px = 320, height_px = 240;
  double mm_per_px = 0.06;
  double gel_thickness_mm = 2.5;
  std::vector<PhotometricLight> lights;  // default: three, see default_lights()
  double diffuse = 1.0;                  // reflectance coefficients of the gel's coating
  double specular = 0.15;
  double shininess = 8.0;
  Eigen::Vector3d ambient_rgb{40, 40, 40};  // the gel's glow without the LEDs' direct light
  double vignetting = 0.1;                  // background this much darker at the corners
  double fps = 25.0;
  std::filesystem::path file;  // where it was read, if from a file

  double pad_width_mm() const { return width_px * mm_per_px; }
  double pad_height_mm() const { return height_px * mm_per_px; }
  // Half the pad's diagonal: the radius of the disc around the centre that the pad covers.
  double pad_half_diagonal_mm() const;
};

// Three lights 120 degrees apart at 35 degrees elevation: red from +x, green,
// blue, each of 110 grey levels.
std::vector<PhotometricLight> default_lights();

// Reads the fields of a `sensor:` mapping with `family: gelsight` (the
// family field itself is read by the caller); problems go to `problems`,
// each naming its field, value and rule.
void read_gelsight_sensor(config::ConfigFields& fields, config::ConfigProblems& problems, GelSightSensor& sensor);

// The `sensor:` section of a scene or sensor file, which must say `family:
// gelsight`. InputError listing every problem.
GelSightSensor load_gelsight_sensor(const std::filesystem::path& file);

// The family a `sensor:` mapping names (its `family` field, marked read);
// an unknown value is a problem naming the field, the value and the choices.
SensorFamily read_sensor_family(config::ConfigFields& fields);

}  // namespace touchcloud::sensor
