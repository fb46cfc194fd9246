// The object of a scene file (`object:`): what the simulator touches and, by
// default, what the chamfer stage scores against, read from one place so the
// two cannot disagree on the mesh, its scale or its pose.
#pragma once

#include <filesystem>
#include <string>

#include <Eigen/Geometry>

#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud {

enum class ObjectKind { Mesh, FoxMask, WaveSurface, Plane };
const char* to_string(ObjectKind kind);

// The object on the table. Its own frame has z up and z = 0 on the table;
// `base_from_object` places it (translation, then yaw; analytic objects
// may only turn about z). The simulator uses its upper surface.
struct ObjectSpec {
  ObjectKind kind = ObjectKind::Plane;
  std::filesystem::path mesh;  // kind Mesh: resolved against the scene file's folder
  double scale = 1.0;          // multiplies object coordinates before the pose
  Eigen::Isometry3d base_from_object = Eigen::Isometry3d::Identity();
  double plane_height_mm = 10.0;  // kind Plane: an unbounded flat top at this height
  SourceLocation where;           // of `object`, for errors found later (an unreadable mesh)
};

// Reads an `object:` mapping; mesh paths are relative to `folder` (the
// scene file's). Problems go to the fields' collector.
void read_object_section(config::ConfigFields& f, ObjectSpec& object, const std::filesystem::path& folder,
                         config::ConfigProblems& problems);
// The `object:` section of a scene file; InputError when it has none.
ObjectSpec load_scene_object(const std::filesystem::path& scene_file);

// The object's mesh (kind Mesh) read and placed in the base frame: scaled,
// then posed. InputError naming the scene's field and the mesh file.
scoring::TriangleMesh read_placed_object_mesh(const ObjectSpec& object);

}  // namespace touchcloud
