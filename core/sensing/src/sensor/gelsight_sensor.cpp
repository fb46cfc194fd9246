#include "touchcloud/sensor/gelsight_sensor.hpp"

#include <cmath>

#include <yaml-cpp/yaml.h>

#include "touchcloud/number_text.hpp"
#include "touchcloud/path_text.hpp"

namespace fs = std::filesystem;

namespace touchcloud::sensor {

using config::ConfigFields;
using config::ConfigProblems;
using config::FieldRule;

namespace {

PhotometricLight light(double azimuth_deg, double elevation_deg, Eigen::Vector3d rgb) {
  const double a = azimuth_deg * M_PI / 180, e = elevation_deg * M_PI / 180;
  return {Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)), rgb};
}

void read_lights(const YAML::Node& node, ConfigFields& f, ConfigProblems& problems, GelSightSensor& sensor) {
  if (!node.IsSequence() || node.size() == 0) {
    f.error("lights", "must be a non-empty list of {direction: [x, y, z], colour_rgb: [r, g, b]}");
    return;
  }
  sensor.lights.clear();
  for (std::size_t i = 0; i < node.size(); ++i) {
    ConfigFields l(node[i], f.field("lights") + "[" + std::to_string(i) + "]", problems);
    const auto d = l.numbers("direction", {0, 0, 1}, 3);
    const auto c = l.numbers("colour_rgb", {0, 0, 0}, 3, FieldRule::NonNegative);
    PhotometricLight light;
    light.direction = Eigen::Vector3d(d[0], d[1], d[2]);
    if (!(light.direction.z() > 0))
      l.error("direction", "z is " + number_text(light.direction.z()) +
                               "; must be > 0 (the LEDs shine from the camera's side of the gel)");
    else light.direction.normalize();
    light.colour_rgb = Eigen::Vector3d(c[0], c[1], c[2]);
    sensor.lights.push_back(light);
  }
}

}  // namespace

const char* to_string(SensorFamily family) {
  return family == SensorFamily::GelSight ? "gelsight" : "gelstereo";
}

double GelSightSensor::pad_half_diagonal_mm() const {
  return 0.5 * std::hypot(pad_width_mm(), pad_height_mm());
}

std::vector<PhotometricLight> default_lights() {
  return {light(0, 35, {110, 0, 0}), light(120, 35, {0, 110, 0}), light(240, 35, {0, 0, 110})};
}

SensorFamily read_sensor_family(ConfigFields& fields) {
  const std::string family = fields.text("family", "gelstereo");
  if (family == "gelstereo") return SensorFamily::GelStereo;
  if (family == "gelsight") return SensorFamily::GelSight;
  fields.error("family", "'" + family + "' is not a sensor family (known: gelstereo, gelsight)");
  return SensorFamily::GelStereo;
}

void read_gelsight_sensor(ConfigFields& f, ConfigProblems& problems, GelSightSensor& s) {
  if (s.lights.empty()) s.lights = default_lights();
  s.name = f.text("name", s.name);
  if (s.name.empty()) f.error("name", "must not be empty (calibrations name the sensor they belong to)");
  const auto size = f.numbers("image_size_px", {double(s.width_px), double(s.height_px)}, 2, FieldRule::Positive);
  s.width_px = static_cast<int>(size[0]);
  s.height_px = static_cast<int>(size[1]);
  if (size[0] != s.width_px || size[1] != s.height_px || s.width_px < 8 || s.height_px < 8)
    f.error("image_size_px", "is [" + number_text(size[0]) + ", " + number_text(size[1]) +
                                 "]; must be whole numbers of pixels, at least 8 each ([width, height])");
  s.mm_per_px = f.number("mm_per_px", s.mm_per_px, FieldRule::Positive);
  s.gel_thickness_mm = f.number("gel_thickness_mm", s.gel_thickness_mm, FieldRule::Positive);
  if (f.has("lights")) read_lights(f.raw("lights"), f, problems, s);
  if (auto r = f.child("reflectance"); f.has("reflectance")) {
    s.diffuse = r->number("diffuse", s.diffuse, FieldRule::NonNegative);
    s.specular = r->number("specular", s.specular, FieldRule::NonNegative);
    s.shininess = r->number("shininess", s.shininess, FieldRule::Positive);
  }
  const auto ambient = f.numbers("ambient_rgb", {s.ambient_rgb[0], s.ambient_rgb[1], s.ambient_rgb[2]}, 3,
                                 FieldRule::NonNegative);
  s.ambient_rgb = Eigen::Vector3d(ambient[0], ambient[1], ambient[2]);
  s.vignetting = f.number("vignetting", s.vignetting, FieldRule::Probability);
  s.fps = f.number("fps", s.fps, FieldRule::Positive);
  if (s.fps > kMaxSensorFps)
    f.error("fps", "is " + number_text(s.fps) + "; must be at most " + number_text(kMaxSensorFps));
}

GelSightSensor load_gelsight_sensor(const fs::path& file) {
  const YAML::Node root = config::load_yaml_file(file, "sensor file");
  if (!root || !root.IsMap() || !root["sensor"] || root["sensor"].IsNull())
    throw InputError("sensor file " + file.string() + " has no 'sensor:' section", {file.string()});
  ConfigProblems problems(file, "sensor file");
  GelSightSensor sensor;
  sensor.file = file;
  {
    ConfigFields fields(root["sensor"], "sensor", problems);
    if (read_sensor_family(fields) != SensorFamily::GelSight && problems.empty())
      fields.error("family", "is gelstereo (or absent); a GelSight-type sensor needs 'family: gelsight'");
    read_gelsight_sensor(fields, problems, sensor);
  }
  problems.throw_if_any();
  return sensor;
}

}  // namespace touchcloud::sensor
