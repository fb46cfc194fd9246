#include "touchcloud/types/scene_object.hpp"

#include <yaml-cpp/yaml.h>

#include "touchcloud/path_text.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

const char* to_string(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::Mesh: return "mesh";
    case ObjectKind::FoxMask: return "fox_mask";
    case ObjectKind::WaveSurface: return "wave_surface";
    case ObjectKind::Plane: return "plane";
  }
  return "?";
}

void read_object_section(config::ConfigFields& f, ObjectSpec& object, const fs::path& folder,
                         config::ConfigProblems& problems) {
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
  object.scale = f.number("scale", 1.0, config::FieldRule::Positive);
  if (object.kind == ObjectKind::Plane) object.plane_height_mm = f.number("height_mm", 10.0, config::FieldRule::Positive);
  else if (f.has("height_mm")) f.error("height_mm", "only the analytic 'plane' has a height_mm");
  if (auto pose = f.child("pose")) {
    Eigen::Vector3d rpy;
    object.base_from_object = config::read_pose(*pose, &rpy);
    if (object.kind != ObjectKind::Mesh && (rpy[0] != 0 || rpy[1] != 0))
      pose->error("rpy_deg", "an analytic surface can only turn about z (roll and pitch must be 0)");
  }
}

ObjectSpec load_scene_object(const fs::path& scene_file) {
  const std::string name = scene_file.string();
  YAML::Node root;
  try {
    root = YAML::LoadFile(name);
  } catch (const YAML::BadFile&) {
    throw InputError("scene file " + absolute_text(scene_file) + " cannot be read", {name});
  } catch (const YAML::Exception& e) {
    throw InputError("scene file " + name + " is not valid YAML: " + e.msg, {name, e.mark.line + 1, e.mark.column + 1});
  }
  if (!root.IsMap() || !root["object"])
    throw InputError("scene file " + name + " has no 'object:' section", {name});
  config::ConfigProblems problems(name);
  ObjectSpec object;
  {
    config::ConfigFields f(root["object"], "object", problems);
    read_object_section(f, object, scene_file.parent_path(), problems);
  }
  problems.throw_if_any();
  return object;
}

scoring::TriangleMesh read_placed_object_mesh(const ObjectSpec& object) {
  if (object.kind != ObjectKind::Mesh)
    throw InputError(std::string("scene object is the analytic surface '") + to_string(object.kind) +
                         "', not a mesh",
                     object.where);
  scoring::TriangleMesh mesh;
  try {
    mesh = scoring::read_triangle_mesh(object.mesh);
  } catch (const InputError& e) {
    throw InputError("scene object.mesh (" + object.mesh.string() + "): " + e.what(), object.where);
  }
  for (auto& v : mesh.vertices) v = object.base_from_object * (object.scale * v);
  return mesh;
}

}  // namespace touchcloud
