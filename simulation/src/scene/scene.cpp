#include "touchcloud/simulation/scene/scene.hpp"
#include "touchcloud/path_text.hpp"

#include <cmath>
#include <fstream>

#include "touchcloud/config/workspace_section.hpp"
#include "touchcloud/config/yaml_fields.hpp"

namespace fs = std::filesystem;

namespace touchcloud::simulation {

using config::ConfigFields;
using config::ConfigProblems;
using config::FieldRule;

namespace {

void read_robot(ConfigFields& f, RobotSpec& robot) {
  robot.speed_mm_s = f.number("speed_mm_s", robot.speed_mm_s, FieldRule::Positive);
  robot.approach_speed_mm_s = f.number("approach_speed_mm_s", robot.approach_speed_mm_s, FieldRule::NonNegative);
  robot.press_depth_mm = f.number("press_depth_mm", robot.press_depth_mm, FieldRule::NonNegative);
  robot.safe_clearance_mm = f.number("safe_clearance_mm", robot.safe_clearance_mm, FieldRule::NonNegative);
  robot.max_contact_depth_mm = f.number("max_contact_depth_mm", robot.max_contact_depth_mm, FieldRule::Positive);
}

// `turntable: {centre_mm: [x, y], angles_deg: [a0, a1, ...]}` or `{centre_mm, step_deg}`.
TurntableSpec read_turntable(ConfigFields& f, ConfigProblems& problems) {
  TurntableSpec t;
  const auto centre = f.numbers("centre_mm", {0, 0}, 2);
  t.centre_mm = Eigen::Vector2d(centre[0], centre[1]);
  const bool has_step = f.has("step_deg");
  t.step_deg = f.number("step_deg", 0.0);
  const YAML::Node angles = f.raw("angles_deg");
  if (angles.IsDefined() && !angles.IsNull()) {
    if (!angles.IsSequence() || angles.size() == 0) {
      problems.add(angles, f.field("angles_deg") + ": must be a list of angles (degrees, one per touch)");
    } else {
      for (std::size_t i = 0; i < angles.size(); ++i) {
        double v = 0;
        if (!angles[i].IsScalar() || !YAML::convert<double>::decode(angles[i], v) || !std::isfinite(v)) {
          problems.add(angles[i], f.field("angles_deg") + "[" + std::to_string(i) + "]: must be a number");
          break;
        }
        t.angles_deg.push_back(v);
      }
    }
    if (has_step) f.error("step_deg", "is set, and so is angles_deg: set one");
  } else if (!has_step) {
    f.error("step_deg", "is missing: a turntable needs angles_deg (one per touch) or step_deg");
  }
  return t;
}

// One effect's own fields (`params` may be absent or null).
void read_effect(Effect effect, const YAML::Node& params, Scene& scene, ConfigProblems& problems) {
  ConfigFields f(params, std::string("effects.") + to_string(effect), problems);
  EffectParameters& p = scene.effect_parameters;
  switch (effect) {
    case Effect::ElasticSpread: p.spread_sigma_mm = f.number("sigma_mm", p.spread_sigma_mm, FieldRule::Positive); break;
    case Effect::PixelNoise:
      p.noise_sigma_grey = f.number("sigma_grey", p.noise_sigma_grey, FieldRule::NonNegative);
      p.noise_sigma_px = f.number("sigma_px", p.noise_sigma_px, FieldRule::NonNegative);
      break;
    case Effect::Blur: p.blur_sigma_px = f.number("sigma_px", p.blur_sigma_px, FieldRule::Positive); break;
    case Effect::MarkerDropout:
      p.dropout_probability = f.number("probability", p.dropout_probability, FieldRule::Probability);
      break;
    case Effect::PoseNoise:
      p.pose_sigma_mm = f.number("sigma_mm", p.pose_sigma_mm, FieldRule::NonNegative);
      p.pose_sigma_deg = f.number("sigma_deg", p.pose_sigma_deg, FieldRule::NonNegative);
      break;
    case Effect::Render:
      p.background_grey = f.number("background_grey", p.background_grey, FieldRule::Positive);
      p.vignetting = f.number("vignetting", p.vignetting, FieldRule::Probability);
      p.marker_grey = f.number("marker_grey", p.marker_grey, FieldRule::NonNegative);
      if (p.background_grey > 255) f.error("background_grey", "must be at most 255");
      if (p.marker_grey >= p.background_grey * (1 - p.vignetting))
        f.error("marker_grey", "must be darker than the background everywhere");
      break;
    case Effect::Vignetting:
      p.lens_fall_off = f.number("fall_off", p.lens_fall_off, FieldRule::Probability);
      break;
    case Effect::ExposureDrift:
      p.exposure_gain = f.number("gain", p.exposure_gain, FieldRule::Positive);
      p.exposure_offset_grey = f.number("offset_grey", p.exposure_offset_grey);
      if (std::abs(p.exposure_offset_grey) > 255) f.error("offset_grey", "must be within -255 to 255");
      break;
    case Effect::GelMarkers:
      p.gel_marker_pitch_mm = f.number("pitch_mm", p.gel_marker_pitch_mm, FieldRule::Positive);
      p.gel_marker_diameter_mm = f.number("diameter_mm", p.gel_marker_diameter_mm, FieldRule::Positive);
      p.gel_marker_darkness = f.number("darkness", p.gel_marker_darkness, FieldRule::Probability);
      p.gel_marker_shift_per_slope_mm =
          f.number("shift_per_slope_mm", p.gel_marker_shift_per_slope_mm, FieldRule::NonNegative);
      if (p.gel_marker_diameter_mm >= p.gel_marker_pitch_mm)
        f.error("diameter_mm", "must be less than pitch_mm (dots that do not touch)");
      break;
    case Effect::Contact:
    case Effect::Refraction:
    case Effect::LensDistortion: break;  // no fields: any given is unknown
  }
}

// `effects:` a list of names or {name: {fields}}, or a mapping name -> fields.
void read_effects(const YAML::Node& node, Scene& scene, ConfigProblems& problems) {
  if (!node || node.IsNull()) return;
  const auto add = [&](const YAML::Node& name_node, const YAML::Node& params, const std::string& field) {
    const std::string name = name_node.as<std::string>("");
    const auto effect = effect_from_name(name);
    if (!effect) {
      problems.add(name_node, field + ": unknown effect '" + name + "' (known: " + effect_names() + ")");
      return;
    }
    if (scene.effects.has(*effect)) {
      problems.add(name_node, field + ": effect '" + name + "' is named twice");
      return;
    }
    scene.effects.add(*effect);
    read_effect(*effect, params, scene, problems);
  };
  if (node.IsMap()) {
    for (const auto& kv : node) add(kv.first, kv.second, "effects." + kv.first.as<std::string>(""));
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node item = node[i];
      const std::string field = "effects[" + std::to_string(i) + "]";
      if (item.IsScalar()) add(item, YAML::Node(), field);
      else if (item.IsMap() && item.size() == 1) add(item.begin()->first, item.begin()->second, field);
      else problems.add(item, field + ": must be an effect name or {name: {fields}}");
    }
  } else {
    problems.add(node, "effects: must be a list of effect names (known: " + effect_names() + ")");
  }
}

}  // namespace

double TurntableSpec::angle_deg(int touch) const {
  if (angles_deg.empty()) return touch * step_deg;
  return angles_deg[static_cast<std::size_t>(touch) % angles_deg.size()];
}

Eigen::Isometry3d TurntableSpec::base_from_object(int touch) const {
  const Eigen::Vector3d centre(centre_mm.x(), centre_mm.y(), 0.0);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(angle_deg(touch) * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = centre - t.linear() * centre;
  return t;
}

Scene load_scene(const fs::path& file) {
  const YAML::Node root = config::load_yaml_file(file, "scene file");
  ConfigProblems problems(file);
  if (!root || root.IsNull()) throw InputError("scene file " + file.string() + " is empty", {file.string()});
  Scene scene;
  scene.file = file;
  scene.sensor.file = file;
  scene.gelsight.file = file;
  scene.name = file.parent_path().filename().string();
  {
    ConfigFields top(root, "", problems);
    scene.name = top.text("name", scene.name);
    top.text("description", "");
    if (auto object = top.child("object")) read_object_section(*object, scene.object, file.parent_path(), problems);
    if (auto workspace = top.child("workspace")) read_workspace_section(*workspace, scene.workspace);
    if (auto fields = top.child("sensor")) {
      scene.family = sensor::read_sensor_family(*fields);
      if (scene.family == sensor::SensorFamily::GelSight) sensor::read_gelsight_sensor(*fields, problems, scene.gelsight);
      else sensor::read_gelstereo_sensor(*fields, problems, scene.sensor);
    }
    if (auto robot = top.child("robot")) read_robot(*robot, scene.robot);
    if (top.has("turntable"))
      if (auto turntable = top.child("turntable")) {
        scene.turntable = read_turntable(*turntable, problems);
        if (scene.object.kind != ObjectKind::Mesh)
          turntable->error("centre_mm", std::string("a turntable turns a mesh object; object is ") +
                                            to_string(scene.object.kind));
      }
    const YAML::Node effects = top.raw("effects");
    read_effects(effects, scene, problems);
    if (scene.family == sensor::SensorFamily::GelSight)
      for (Effect e : {Effect::Refraction, Effect::LensDistortion, Effect::MarkerDropout})
        if (scene.effects.has(e))
          problems.add(effects, std::string("effects: '") + to_string(e) +
                                    "' does not apply to sensor.family gelsight (a flat gel without markers, seen "
                                    "straight on); remove it");
    if (scene.family == sensor::SensorFamily::GelStereo)
      for (Effect e : {Effect::Vignetting, Effect::ExposureDrift})
        if (scene.effects.has(e))
          problems.add(effects, std::string("effects: '") + to_string(e) +
                                    "' applies to sensor.family gelsight only (the GelStereo's render effect has its "
                                    "own vignetting); remove it");
    if (scene.family == sensor::SensorFamily::GelStereo && scene.effects.has(Effect::GelMarkers))
      problems.add(effects, "effects: 'markers' applies to sensor.family gelsight (dots printed on its flat gel); a "
                            "GelStereo's markers are its gel's marker layout, drawn by 'render'");
  }
  problems.throw_if_any();
  return scene;
}

}  // namespace touchcloud::simulation
