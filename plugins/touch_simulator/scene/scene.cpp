#include "scene/scene.hpp"

#include <cmath>
#include <fstream>

#include "scene/scene_fields.hpp"

namespace fs = std::filesystem;

namespace touchcloud::sim {

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

constexpr double kDegToRad = M_PI / 180.0;

Eigen::Matrix3d rpy_rotation(const std::vector<double>& rpy_deg) {
  return (Eigen::AngleAxisd(rpy_deg[2] * kDegToRad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy_deg[1] * kDegToRad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy_deg[0] * kDegToRad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// {xyz_mm: [x, y, z], rpy_deg: [roll, pitch, yaw]}: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Isometry3d read_pose(SceneFields& pose, Eigen::Vector3d* rpy_out = nullptr) {
  const auto xyz = pose.numbers("xyz_mm", {0, 0, 0}, 3);
  const auto rpy = pose.numbers("rpy_deg", {0, 0, 0}, 3);
  if (rpy_out) *rpy_out = {rpy[0], rpy[1], rpy[2]};
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rpy_rotation(rpy);
  t.translation() = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
  return t;
}

void read_object(SceneFields& f, ObjectSpec& object, const fs::path& folder, SceneProblems& problems) {
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
  object.scale = f.number("scale", 1.0, Rule::Positive);
  if (object.kind == ObjectKind::Plane) object.plane_height_mm = f.number("height_mm", 10.0, Rule::Positive);
  else if (f.has("height_mm")) f.error("height_mm", "only the analytic 'plane' has a height_mm");
  if (auto pose = f.child("pose")) {
    Eigen::Vector3d rpy;
    object.base_from_object = read_pose(*pose, &rpy);
    if (object.kind != ObjectKind::Mesh && (rpy[0] != 0 || rpy[1] != 0))
      pose->error("rpy_deg", "an analytic surface can only turn about z (roll and pitch must be 0)");
  }
}

void read_workspace(SceneFields& f, Workspace& w) {
  const auto x = f.numbers("x_mm", {w.x_mm[0], w.x_mm[1]}, 2);
  const auto y = f.numbers("y_mm", {w.y_mm[0], w.y_mm[1]}, 2);
  if (!(x[0] < x[1])) f.error("x_mm", "must be [min, max] with min < max");
  if (!(y[0] < y[1])) f.error("y_mm", "must be [min, max] with min < max");
  w.x_mm = {x[0], x[1]};
  w.y_mm = {y[0], y[1]};
  const auto grid = f.numbers("grid", {double(w.cells_x), double(w.cells_y)}, 2, Rule::Positive);
  if (grid[0] != std::floor(grid[0]) || grid[1] != std::floor(grid[1]) || grid[0] > 1e4 || grid[1] > 1e4)
    f.error("grid", "must be two whole numbers of cells [nx, ny], each >= 1");
  else {
    w.cells_x = static_cast<int>(grid[0]);
    w.cells_y = static_cast<int>(grid[1]);
  }
}

optics::CameraIntrinsics read_intrinsics(SceneFields& f, const optics::CameraIntrinsics& fallback,
                                         SceneProblems& problems) {
  optics::CameraIntrinsics c = fallback;
  c.width_px = f.integer("width_px", c.width_px, 1);
  c.height_px = f.integer("height_px", c.height_px, 1);
  c.fx_px = f.number("fx_px", c.fx_px, Rule::Positive);
  c.fy_px = f.number("fy_px", c.fy_px, Rule::Positive);
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

void read_cameras(SceneFields& f, Scene& scene, SceneProblems& problems) {
  CameraSpec& cams = scene.cameras;
  cams.where = problems.where(f.node());
  // A lens a little barrel-distorted, as small board cameras are; used only
  // with the lens_distortion effect.
  optics::CameraIntrinsics defaults;
  defaults.distortion = {-0.05, 0.02, 0.0005, -0.0003, 0.0};
  if (auto left = f.child("left")) cams.left = read_intrinsics(*left, defaults, problems);
  if (auto right = f.child("right")) cams.right = read_intrinsics(*right, cams.left, problems);

  if (f.has("baseline_mm") && f.has("right_from_left"))
    f.error("baseline_mm", "give either baseline_mm or right_from_left, not both");
  if (f.has("plate_gap_mm") && f.has("sensor_from_left_camera"))
    f.error("plate_gap_mm", "give either plate_gap_mm or sensor_from_left_camera, not both");
  const double baseline = f.number("baseline_mm", kDefaultBaselineMm, Rule::Positive);
  const double gap = f.number("plate_gap_mm", kDefaultPlateGapMm, Rule::Positive);

  Eigen::Isometry3d sensor_from_left = Eigen::Isometry3d::Identity();
  sensor_from_left.translation() = Eigen::Vector3d(-0.5 * baseline, 0, -(scene.plate.thickness_mm + gap));
  if (auto pose = f.child("sensor_from_left_camera"); f.has("sensor_from_left_camera")) sensor_from_left = read_pose(*pose);
  cams.right_from_left = Eigen::Isometry3d::Identity();
  cams.right_from_left.translation() = Eigen::Vector3d(-baseline, 0, 0);
  if (auto pose = f.child("right_from_left"); f.has("right_from_left")) cams.right_from_left = read_pose(*pose);

  const Eigen::Matrix3d housing_from_plate =
      rpy_rotation({scene.plate.tilt_deg[0], scene.plate.tilt_deg[1], 0.0});
  cams.sensor_from_left_camera = Eigen::Isometry3d(housing_from_plate.transpose()) * sensor_from_left;
}

void read_plate(SceneFields& f, PlateSpec& plate) {
  plate.thickness_mm = f.number("thickness_mm", plate.thickness_mm, Rule::Positive);
  const auto tilt = f.numbers("tilt_deg", {0, 0}, 2);
  if (std::abs(tilt[0]) >= 90 || std::abs(tilt[1]) >= 90) f.error("tilt_deg", "each tilt must be within (-90, 90)");
  else plate.tilt_deg = {tilt[0], tilt[1]};
  plate.mu_air = f.number("mu_air", plate.mu_air, Rule::Positive);
  plate.mu_acrylic = f.number("mu_acrylic", plate.mu_acrylic, Rule::Positive);
  plate.mu_silicone = f.number("mu_silicone", plate.mu_silicone, Rule::Positive);
}

void read_sensor(SceneFields& f, Scene& scene, SceneProblems& problems) {
  if (auto gel = f.child("gel")) scene.gel.diameter_mm = gel->number("diameter_mm", scene.gel.diameter_mm, Rule::Positive);
  if (auto m = f.child("markers")) {
    MarkerSpec& markers = scene.markers;
    markers.min_spacing_mm = m->number("min_spacing_mm", markers.min_spacing_mm, Rule::Positive);
    markers.mean_spacing_mm = m->number("mean_spacing_mm", markers.mean_spacing_mm, Rule::Positive);
    markers.diameter_mm = m->number("diameter_mm", markers.diameter_mm, Rule::Positive);
    markers.seed = m->seed("seed", markers.seed);
    if (markers.mean_spacing_mm < markers.min_spacing_mm)
      m->error("mean_spacing_mm", "must be >= min_spacing_mm (" + std::to_string(markers.min_spacing_mm) + ")");
    if (markers.diameter_mm >= markers.min_spacing_mm)
      m->error("diameter_mm", "must be < min_spacing_mm: dots would touch");
    if (markers.min_spacing_mm > 0.5 * scene.gel.diameter_mm)
      m->error("min_spacing_mm", "must be well below the gel's diameter");
  }
  {
    auto plate = f.child("plate");
    scene.plate_where = problems.where(plate->node());
    read_plate(*plate, scene.plate);
  }
  {
    auto cameras = f.child("cameras");
    read_cameras(*cameras, scene, problems);
  }
  scene.fps = f.number("fps", scene.fps, Rule::Positive);
}

void read_robot(SceneFields& f, RobotSpec& robot) {
  robot.speed_mm_s = f.number("speed_mm_s", robot.speed_mm_s, Rule::Positive);
  robot.press_depth_mm = f.number("press_depth_mm", robot.press_depth_mm, Rule::NonNegative);
  robot.safe_clearance_mm = f.number("safe_clearance_mm", robot.safe_clearance_mm, Rule::NonNegative);
  robot.max_contact_depth_mm = f.number("max_contact_depth_mm", robot.max_contact_depth_mm, Rule::Positive);
}

// One effect's own fields (`params` may be absent or null).
void read_effect(Effect effect, const YAML::Node& params, Scene& scene, SceneProblems& problems) {
  SceneFields f(params, std::string("effects.") + to_string(effect), problems);
  EffectParameters& p = scene.effect_parameters;
  switch (effect) {
    case Effect::ElasticSpread: p.spread_sigma_mm = f.number("sigma_mm", p.spread_sigma_mm, Rule::Positive); break;
    case Effect::PixelNoise:
      p.noise_sigma_grey = f.number("sigma_grey", p.noise_sigma_grey, Rule::NonNegative);
      p.noise_sigma_px = f.number("sigma_px", p.noise_sigma_px, Rule::NonNegative);
      break;
    case Effect::Blur: p.blur_sigma_px = f.number("sigma_px", p.blur_sigma_px, Rule::Positive); break;
    case Effect::MarkerDropout:
      p.dropout_probability = f.number("probability", p.dropout_probability, Rule::Probability);
      break;
    case Effect::PoseNoise:
      p.pose_sigma_mm = f.number("sigma_mm", p.pose_sigma_mm, Rule::NonNegative);
      p.pose_sigma_deg = f.number("sigma_deg", p.pose_sigma_deg, Rule::NonNegative);
      break;
    case Effect::Render:
      p.background_grey = f.number("background_grey", p.background_grey, Rule::Positive);
      p.vignetting = f.number("vignetting", p.vignetting, Rule::Probability);
      p.marker_grey = f.number("marker_grey", p.marker_grey, Rule::NonNegative);
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
void read_effects(const YAML::Node& node, Scene& scene, SceneProblems& problems) {
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
  SceneProblems problems(file);
  if (!root || root.IsNull()) throw InputError("scene file " + file.string() + " is empty", {file.string()});
  Scene scene;
  scene.file = file;
  scene.name = file.parent_path().filename().string();
  {
    SceneFields top(root, "", problems);
    scene.name = top.text("name", scene.name);
    top.text("description", "");
    if (auto object = top.child("object")) read_object(*object, scene.object, file.parent_path(), problems);
    if (auto workspace = top.child("workspace")) read_workspace(*workspace, scene.workspace);
    if (auto sensor = top.child("sensor")) read_sensor(*sensor, scene, problems);
    if (auto robot = top.child("robot")) read_robot(*robot, scene.robot);
    read_effects(top.raw("effects"), scene, problems);
  }
  problems.throw_if_any();
  return scene;
}

}  // namespace touchcloud::sim
