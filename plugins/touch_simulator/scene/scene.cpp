#include "scene/scene.hpp"

#include <cmath>
#include <fstream>

#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/types/workspace_parameters.hpp"

namespace fs = std::filesystem;

namespace touchcloud::touch_simulator {

using config::ConfigFields;
using config::ConfigProblems;
using config::FieldRule;

const char* to_string(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::Mesh: return "mesh";
    case ObjectKind::FoxMask: return "fox_mask";
    case ObjectKind::WaveSurface: return "wave_surface";
    case ObjectKind::Plane: return "plane";
  }
  return "?";
}


namespace {

void read_object(ConfigFields& f, ObjectSpec& object, const fs::path& folder, ConfigProblems& problems) {
  object.where = problems.where(f.node());
  const bool has_mesh = f.has("mesh"), has_analytic = f.has("analytic");
  if (has_mesh == has_analytic) f.error("mesh", "give exactly one of 'mesh' (a file) or 'analytic' (a surface name)");
  if (has_mesh) {
    object.kind = ObjectKind::Mesh;
    const fs::path mesh = f.text("mesh", "");
    object.mesh = (mesh.is_relative() ? folder / mesh : mesh).lexically_normal();
  } else if (has_analytic) {
    const std::string name = f.text("analytic", "plane");
    if (name == "fox_mask") object.kind = ObjectKind::FoxMask;
    else if (name == "wave_surface") object.kind = ObjectKind::WaveSurface;
    else if (name == "plane") object.kind = ObjectKind::Plane;
    else f.error("analytic", "unknown surface '" + name + "' (known: fox_mask, wave_surface, plane)");
  }
  object.scale = f.number("scale", 1.0, FieldRule::Positive);
  if (object.kind == ObjectKind::Plane) object.plane_height_mm = f.number("height_mm", 10.0, FieldRule::Positive);
  else if (f.has("height_mm")) f.error("height_mm", "only the analytic 'plane' has a height_mm");
  if (auto pose = f.child("pose")) {
    Eigen::Vector3d rpy;
    object.base_from_object = config::read_pose(*pose, &rpy);
    if (object.kind != ObjectKind::Mesh && (rpy[0] != 0 || rpy[1] != 0))
      pose->error("rpy_deg", "an analytic surface can only turn about z (roll and pitch must be 0)");
  }
}

void read_robot(ConfigFields& f, RobotSpec& robot) {
  robot.speed_mm_s = f.number("speed_mm_s", robot.speed_mm_s, FieldRule::Positive);
  robot.approach_speed_mm_s = f.number("approach_speed_mm_s", robot.approach_speed_mm_s, FieldRule::NonNegative);
  robot.press_depth_mm = f.number("press_depth_mm", robot.press_depth_mm, FieldRule::NonNegative);
  robot.safe_clearance_mm = f.number("safe_clearance_mm", robot.safe_clearance_mm, FieldRule::NonNegative);
  robot.max_contact_depth_mm = f.number("max_contact_depth_mm", robot.max_contact_depth_mm, FieldRule::Positive);
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

Scene load_scene(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw InputError("scene file " + file.string() + " does not exist or is not a file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw InputError("scene file " + file.string() + " is not valid YAML: " + e.msg,
                     {file.string(), e.mark.line + 1, e.mark.column + 1});
  }
  ConfigProblems problems(file);
  if (!root || root.IsNull()) throw InputError("scene file " + file.string() + " is empty", {file.string()});
  Scene scene;
  scene.file = file;
  scene.sensor.file = file;
  scene.name = file.parent_path().filename().string();
  {
    ConfigFields top(root, "", problems);
    scene.name = top.text("name", scene.name);
    top.text("description", "");
    if (auto object = top.child("object")) read_object(*object, scene.object, file.parent_path(), problems);
    if (auto workspace = top.child("workspace")) read_workspace_section(*workspace, scene.workspace);
    if (auto fields = top.child("sensor")) sensor::read_gelstereo_sensor(*fields, problems, scene.sensor);
    if (auto robot = top.child("robot")) read_robot(*robot, scene.robot);
    read_effects(top.raw("effects"), scene, problems);
  }
  problems.throw_if_any();
  return scene;
}

}  // namespace touchcloud::touch_simulator
