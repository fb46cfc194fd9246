#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/sensor/gelsight_sensor.hpp"
#include "touchcloud/path_text.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/file_write.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "touchcloud/optics/refractive_projection.hpp"

namespace fs = std::filesystem;

namespace touchcloud::sensor {

using config::ConfigFields;
using config::ConfigProblems;
using config::FieldRule;

namespace {

Eigen::Matrix3d housing_from_plate(const PlateSpec& plate) {
  return config::rpy_rotation(plate.tilt_deg[0], plate.tilt_deg[1], 0.0);
}

optics::CameraIntrinsics read_intrinsics(ConfigFields& f, const optics::CameraIntrinsics& fallback,
                                         ConfigProblems& problems) {
  optics::CameraIntrinsics c = fallback;
  c.width_px = f.integer("width_px", c.width_px, 1);
  c.height_px = f.integer("height_px", c.height_px, 1);
  c.fx_px = f.number("fx_px", c.fx_px, FieldRule::Positive);
  c.fy_px = f.number("fy_px", c.fy_px, FieldRule::Positive);
  c.cx_px = f.number("cx_px", c.cx_px);
  c.cy_px = f.number("cy_px", c.cy_px);
  const auto& d = c.distortion;
  const auto k = f.numbers("distortion", {d.k1, d.k2, d.p1, d.p2, d.k3}, 5);
  c.distortion = {k[0], k[1], k[2], k[3], k[4]};
  try {
    c.validate(f.path().c_str());
  } catch (const InputError& e) {
    for (const auto& d2 : e.diagnostics()) problems.add(f.node(), d2.message);
  }
  return c;
}

void read_cameras(ConfigFields& f, GelStereoSensor& sensor, ConfigProblems& problems) {
  CameraSpec& cams = sensor.cameras;
  sensor.cameras_where = problems.where(f.node());
  // A lens a little barrel-distorted, as small board cameras are; used only
  // where lens distortion is modelled.
  optics::CameraIntrinsics defaults;
  defaults.distortion = {-0.05, 0.02, 0.0005, -0.0003, 0.0};
  cams.left = defaults;
  if (auto left = f.child("left")) cams.left = read_intrinsics(*left, defaults, problems);
  cams.right = cams.left;
  if (auto right = f.child("right")) cams.right = read_intrinsics(*right, cams.left, problems);

  if (f.has("baseline_mm") && f.has("right_from_left"))
    f.error("baseline_mm", "give either baseline_mm or right_from_left, not both");
  if (f.has("plate_gap_mm") && f.has("sensor_from_left_camera"))
    f.error("plate_gap_mm", "give either plate_gap_mm or sensor_from_left_camera, not both");
  const double baseline = f.number("baseline_mm", kDefaultBaselineMm, FieldRule::Positive);
  const double gap = f.number("plate_gap_mm", kDefaultPlateGapMm, FieldRule::Positive);

  cams.housing_from_left_camera = Eigen::Isometry3d::Identity();
  cams.housing_from_left_camera.translation() =
      Eigen::Vector3d(-0.5 * baseline, 0, -(sensor.plate.thickness_mm + gap));
  if (auto pose = f.child("sensor_from_left_camera"); f.has("sensor_from_left_camera"))
    cams.housing_from_left_camera = config::read_pose(*pose);
  cams.right_from_left = Eigen::Isometry3d::Identity();
  cams.right_from_left.translation() = Eigen::Vector3d(-baseline, 0, 0);
  if (auto pose = f.child("right_from_left"); f.has("right_from_left")) cams.right_from_left = config::read_pose(*pose);
}

void read_plate(ConfigFields& f, PlateSpec& plate) {
  plate.thickness_mm = f.number("thickness_mm", plate.thickness_mm, FieldRule::Positive);
  const auto tilt = f.numbers("tilt_deg", {plate.tilt_deg[0], plate.tilt_deg[1]}, 2);
  if (std::abs(tilt[0]) >= 90 || std::abs(tilt[1]) >= 90) f.error("tilt_deg", "each tilt must be within (-90, 90)");
  else plate.tilt_deg = {tilt[0], tilt[1]};
  plate.mu_air = f.number("mu_air", plate.mu_air, FieldRule::Positive);
  plate.mu_acrylic = f.number("mu_acrylic", plate.mu_acrylic, FieldRule::Positive);
  plate.mu_silicone = f.number("mu_silicone", plate.mu_silicone, FieldRule::Positive);
}

void read_markers(ConfigFields& m, const GelSpec& gel, MarkerSpec& markers) {
  markers.min_spacing_mm = m.number("min_spacing_mm", markers.min_spacing_mm, FieldRule::Positive);
  markers.mean_spacing_mm = m.number("mean_spacing_mm", markers.mean_spacing_mm, FieldRule::Positive);
  markers.diameter_mm = m.number("diameter_mm", markers.diameter_mm, FieldRule::Positive);
  markers.seed = m.seed("seed", markers.seed);
  if (markers.mean_spacing_mm < markers.min_spacing_mm)
    m.error("mean_spacing_mm", "must be >= min_spacing_mm (" + number_text(markers.min_spacing_mm) + ")");
  if (markers.diameter_mm >= markers.min_spacing_mm) m.error("diameter_mm", "must be < min_spacing_mm: dots would touch");
  if (markers.min_spacing_mm > 0.5 * gel.diameter_mm) m.error("min_spacing_mm", "must be well below the gel's diameter");
}

void read_pattern(ConfigFields& f, GelStereoSensor& sensor) {
  const std::string pattern = f.text("pattern", "markers");
  if (pattern == "markers") sensor.pattern = GelPattern::Markers;
  else if (pattern == "colour_pattern") sensor.pattern = GelPattern::ColourPattern;
  else f.error("pattern", "'" + pattern + "' is not one of: markers, colour_pattern");
  if (!f.has("colour_pattern")) return;
  if (sensor.pattern != GelPattern::ColourPattern)
    f.error("colour_pattern", "is given, but pattern is not colour_pattern");
  auto c = f.child("colour_pattern");
  ColourPatternSpec& p = sensor.colour_pattern;
  p.feature_mm = c->number("feature_mm", p.feature_mm, FieldRule::Positive);
  p.opacity = c->number("opacity", p.opacity, FieldRule::Probability);
  p.seed = c->seed("seed", p.seed);
  p.vignetting = c->number("vignetting", p.vignetting, FieldRule::Probability);
  const auto size = c->numbers("image_size_px", {0.0, 0.0}, 2, FieldRule::NonNegative);
  if (size[0] != std::floor(size[0]) || size[1] != std::floor(size[1]) || size[0] > 8192 || size[1] > 8192)
    c->error("image_size_px", "must be two whole numbers in [0, 8192] (0: the left camera's size)");
  else {
    p.width_px = static_cast<int>(size[0]);
    p.height_px = static_cast<int>(size[1]);
  }
  p.surface_grid_mm = c->number("surface_grid_mm", p.surface_grid_mm, FieldRule::Positive);
  if (p.surface_grid_mm < 0.02 || p.surface_grid_mm > 2.0)
    c->error("surface_grid_mm", "must be in [0.02, 2] mm");
}

optics::PinholeCamera camera(optics::CameraIntrinsics intrinsics, bool lens_distortion) {
  if (!lens_distortion) intrinsics.distortion = {};
  return optics::PinholeCamera(intrinsics);
}

optics::RefractivePlate plate_in_sensor_frame(const PlateSpec& spec, bool refraction) {
  optics::RefractivePlate plate;  // the sensor frame's origin is on the gel-side face
  plate.normal = Eigen::Vector3d::UnitZ();
  plate.distance_mm = -spec.thickness_mm;
  plate.thickness_mm = spec.thickness_mm;
  if (refraction) {
    plate.mu_air = spec.mu_air;
    plate.mu_acrylic = spec.mu_acrylic;
    plate.mu_silicone = spec.mu_silicone;
  } else {
    plate.mu_air = plate.mu_acrylic = plate.mu_silicone = 1.0;  // straight rays
  }
  return plate;
}

// Refuses a plate through which no ray of a camera reaches the silicone.
void require_rays_through_plate(const optics::StereoRig& rig, optics::StereoSide side, const GelStereoSensor& sensor) {
  const auto& in = rig.camera(side).intrinsics();
  int through = 0, reflected = 0, missed = 0;
  constexpr int kSteps = 32;
  for (int iy = 0; iy <= kSteps; ++iy)
    for (int ix = 0; ix <= kSteps; ++ix) {
      const Eigen::Vector2d px((in.width_px - 1.0) * ix / kSteps, (in.height_px - 1.0) * iy / kSteps);
      const auto ray = optics::back_project_refracted(rig, side, px);
      if (ray.status == optics::TraceStatus::Ok) ++through;
      else if (ray.status == optics::TraceStatus::TotalInternalReflection) ++reflected;
      else ++missed;
    }
  if (through > 0) return;
  const PlateSpec& p = sensor.plate;
  std::ostringstream s;
  s << "sensor.plate: with mu_air = " << p.mu_air << ", mu_acrylic = " << p.mu_acrylic
    << ", mu_silicone = " << p.mu_silicone << " and tilt_deg = [" << p.tilt_deg[0] << ", " << p.tilt_deg[1]
    << "] no ray of the " << optics::to_string(side) << " camera reaches the gel: of " << (kSteps + 1) * (kSteps + 1)
    << " sampled pixels, " << reflected << " are totally reflected and " << missed << " miss the plate";
  throw InputError(s.str(), sensor.plate_where);
}

void emit_pose(YAML::Emitter& out, const char* key, const Eigen::Isometry3d& pose) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): Eigen's Z-Y-X angles give (yaw, pitch, roll).
  const Eigen::Vector3d ypr = pose.linear().eulerAngles(2, 1, 0) * (180.0 / M_PI);
  const Eigen::Vector3d t = pose.translation();
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "xyz_mm" << YAML::Value << YAML::Flow << std::vector<double>{t.x(), t.y(), t.z()};
  out << YAML::Key << "rpy_deg" << YAML::Value << YAML::Flow << std::vector<double>{ypr[2], ypr[1], ypr[0]};
  out << YAML::EndMap;
}

void emit_intrinsics(YAML::Emitter& out, const char* key, const optics::CameraIntrinsics& c) {
  const auto& d = c.distortion;
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "width_px" << YAML::Value << c.width_px << YAML::Key << "height_px" << YAML::Value << c.height_px;
  out << YAML::Key << "fx_px" << YAML::Value << c.fx_px << YAML::Key << "fy_px" << YAML::Value << c.fy_px;
  out << YAML::Key << "cx_px" << YAML::Value << c.cx_px << YAML::Key << "cy_px" << YAML::Value << c.cy_px;
  out << YAML::Key << "distortion" << YAML::Value << YAML::Flow << std::vector<double>{d.k1, d.k2, d.p1, d.p2, d.k3};
  out << YAML::EndMap;
}

}  // namespace

Eigen::Isometry3d GelStereoSensor::sensor_from_left_camera() const {
  return Eigen::Isometry3d(Eigen::Matrix3d(housing_from_plate(plate).transpose())) * cameras.housing_from_left_camera;
}

void read_gelstereo_sensor(ConfigFields& f, ConfigProblems& problems, GelStereoSensor& sensor) {
  if (auto gel = f.child("gel")) sensor.gel.diameter_mm = gel->number("diameter_mm", sensor.gel.diameter_mm, FieldRule::Positive);
  if (auto markers = f.child("markers")) read_markers(*markers, sensor.gel, sensor.markers);
  read_pattern(f, sensor);
  {
    auto plate = f.child("plate");  // before the cameras: their default height needs the thickness
    sensor.plate_where = problems.where(plate->node());
    read_plate(*plate, sensor.plate);
  }
  {
    auto cameras = f.child("cameras");
    read_cameras(*cameras, sensor, problems);
  }
  sensor.fps = f.number("fps", sensor.fps, FieldRule::Positive);
  // Frames are simulated one by one: more than a high-speed camera gives
  // would take forever (or, near the largest double, move the robot by 0).
  if (sensor.fps > kMaxSensorFps) {
    f.error("fps", number_text(sensor.fps) + " frames per second is more than a camera gives (at most " +
                       number_text(kMaxSensorFps) + ")");
    sensor.fps = kMaxSensorFps;
  }
}

GelStereoSensor load_gelstereo_sensor(const fs::path& file) {
  const YAML::Node root = config::load_yaml_file(file, "sensor file");
  if (!root || !root.IsMap() || !root["sensor"] || root["sensor"].IsNull())
    throw InputError("sensor file " + file.string() + " has no 'sensor:' section (gel, markers, plate, cameras)",
                     {file.string()});
  ConfigProblems problems(file, "sensor file");
  GelStereoSensor sensor;
  sensor.file = file;
  {
    ConfigFields fields(root["sensor"], "sensor", problems);
    if (read_sensor_family(fields) == SensorFamily::GelSight) {
      fields.error("family", "is gelsight: a GelSight-type sensor, not the GelStereo (gel, markers, plate, "
                             "cameras) this stage needs");
      for (const auto& kv : fields.node()) fields.raw(kv.first.as<std::string>(""));  // one problem, not one per field
    } else {
      read_gelstereo_sensor(fields, problems, sensor);
    }
  }
  problems.throw_if_any();
  return sensor;
}

GelStereoSensor load_sensor_parameter(const std::string& file, const std::string& parameter, bool refraction,
                                      bool lens_distortion) {
  try {
    GelStereoSensor sensor = load_gelstereo_sensor(file);
    make_stereo_rig(sensor, refraction, lens_distortion);
    return sensor;
  } catch (const InputError& e) {
    throw ParameterError(parameter, e.what());
  }
}

optics::StereoRig make_stereo_rig(const GelStereoSensor& sensor, bool refraction, bool lens_distortion) {
  const Eigen::Isometry3d left_from_sensor = sensor.sensor_from_left_camera().inverse();
  const auto rig = [&] {
    try {
      return optics::StereoRig(camera(sensor.cameras.left, lens_distortion),
                               camera(sensor.cameras.right, lens_distortion), sensor.cameras.right_from_left,
                               plate_in_sensor_frame(sensor.plate, refraction).expressed_in(left_from_sensor));
    } catch (const InputError& e) {
      throw InputError(std::string("sensor.cameras: the cameras and the plate do not fit together: ") + e.what(),
                       sensor.cameras_where);
    }
  }();
  if (refraction) {
    require_rays_through_plate(rig, optics::StereoSide::Left, sensor);
    require_rays_through_plate(rig, optics::StereoSide::Right, sensor);
  }
  return rig;
}

void set_plate_from_left_frame(GelStereoSensor& sensor, const optics::RefractivePlate& plate_left) {
  plate_left.validate("plate_left");
  CameraSpec& cams = sensor.cameras;
  // The plate normal in housing axes is R z with R = Ry(tilt_y) Rx(tilt_x),
  // i.e. (sin ty cos tx, -sin tx, cos ty cos tx).
  const Eigen::Vector3d m = (cams.housing_from_left_camera.linear() * plate_left.normal).normalized();
  const double tilt_x = -std::asin(std::clamp(m.y(), -1.0, 1.0));
  const double tilt_y = std::atan2(m.x(), m.z());
  sensor.plate.tilt_deg = Eigen::Vector2d(tilt_x, tilt_y) * (180.0 / M_PI);
  // The camera-side face lies at -thickness along the sensor z; the left
  // centre must sit plate_left.distance_mm below it. Moving the camera along
  // m (the normal in housing axes) changes that distance one for one.
  const double centre_height_now = m.dot(cams.housing_from_left_camera.translation());
  const double centre_height_wanted = -sensor.plate.thickness_mm - plate_left.distance_mm;
  cams.housing_from_left_camera.translation() += (centre_height_wanted - centre_height_now) * m;
  const double scale = sensor.plate.mu_air / plate_left.mu_air;  // only ratios matter
  sensor.plate.mu_acrylic = plate_left.mu_acrylic * scale;
  sensor.plate.mu_silicone = plate_left.mu_silicone * scale;
}

void write_gelstereo_sensor(const GelStereoSensor& sensor, const fs::path& file, const std::string& comment) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap << YAML::Key << "sensor" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "gel" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "diameter_mm"
      << YAML::Value << sensor.gel.diameter_mm << YAML::EndMap;
  const MarkerSpec& m = sensor.markers;
  out << YAML::Key << "markers" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "min_spacing_mm" << YAML::Value << m.min_spacing_mm << YAML::Key << "mean_spacing_mm"
      << YAML::Value << m.mean_spacing_mm << YAML::Key << "diameter_mm" << YAML::Value << m.diameter_mm
      << YAML::Key << "seed" << YAML::Value << m.seed << YAML::EndMap;
  // Written only for the colour pattern, so marker sensor files stay as they were.
  if (sensor.pattern == GelPattern::ColourPattern) {
    const ColourPatternSpec& c = sensor.colour_pattern;
    out << YAML::Key << "pattern" << YAML::Value << "colour_pattern";
    out << YAML::Key << "colour_pattern" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "feature_mm" << YAML::Value << c.feature_mm << YAML::Key << "opacity" << YAML::Value
        << c.opacity << YAML::Key << "seed" << YAML::Value << c.seed << YAML::Key << "vignetting" << YAML::Value
        << c.vignetting << YAML::Key << "image_size_px" << YAML::Value << YAML::Flow
        << std::vector<int>{c.width_px, c.height_px} << YAML::Key << "surface_grid_mm" << YAML::Value
        << c.surface_grid_mm << YAML::EndMap;
  }
  const PlateSpec& p = sensor.plate;
  out << YAML::Key << "plate" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "thickness_mm" << YAML::Value << p.thickness_mm;
  out << YAML::Key << "tilt_deg" << YAML::Value << YAML::Flow << std::vector<double>{p.tilt_deg[0], p.tilt_deg[1]};
  out << YAML::Key << "mu_air" << YAML::Value << p.mu_air << YAML::Key << "mu_acrylic" << YAML::Value << p.mu_acrylic
      << YAML::Key << "mu_silicone" << YAML::Value << p.mu_silicone << YAML::EndMap;
  out << YAML::Key << "cameras" << YAML::Value << YAML::BeginMap;
  emit_intrinsics(out, "left", sensor.cameras.left);
  emit_intrinsics(out, "right", sensor.cameras.right);
  emit_pose(out, "sensor_from_left_camera", sensor.cameras.housing_from_left_camera);
  emit_pose(out, "right_from_left", sensor.cameras.right_from_left);
  out << YAML::EndMap;
  out << YAML::Key << "fps" << YAML::Value << sensor.fps;
  out << YAML::EndMap << YAML::EndMap;

  fs::path temporary = file;
  temporary += ".partial";
  std::ostringstream text;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) text << "# " << line << "\n";
  text << out.c_str() << "\n";
  std::error_code ec;
  try {
    write_file(temporary, text.str());  // checks every write and the close
  } catch (...) {
    fs::remove(temporary, ec);
    throw;
  }
  fs::rename(temporary, file, ec);
  if (ec) throw InputError("cannot write sensor file " + file.string() + ": " + ec.message());
}

}  // namespace touchcloud::sensor
