// A scene file: the object on the table, the sensor (gel, markers, plate,
// cameras), the robot's touch motion and the effects to simulate. Lengths in
// mm, angles in degrees. See sample_clouds/README.md for the format.
#pragma once

#include <filesystem>
#include <string>

#include <Eigen/Geometry>

#include "scene/effects.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/optics/pinhole_camera.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud::sim {

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

// Where touches may go, and the paper's grid of sampling positions over it.
using Workspace = WorkspaceGrid;

struct GelSpec {
  double diameter_mm = 65.0;  // a hemisphere
  double radius_mm() const { return 0.5 * diameter_mm; }
};

struct MarkerSpec {
  double min_spacing_mm = 1.5;   // no two markers closer
  double mean_spacing_mm = 1.8;  // mean distance to the nearest marker
  double diameter_mm = 0.6;      // printed dot, for rendering
  std::uint64_t seed = 1;        // the layout is a property of the gel, not of a run
};

struct PlateSpec {
  double thickness_mm = 5.0;
  // The plate, with the gel on it, turned about the sensor origin's x and y
  // axes relative to the cameras (what refractive calibration estimates).
  Eigen::Vector2d tilt_deg = Eigen::Vector2d::Zero();
  double mu_air = 1.0, mu_acrylic = 1.49, mu_silicone = 1.41;
};

struct CameraSpec {
  optics::CameraIntrinsics left, right;  // distortion used only with lens_distortion
  // Pose of the left camera (OpenCV axes) in the sensor frame, the plate's
  // tilt included; the right camera's pose relative to it.
  Eigen::Isometry3d sensor_from_left_camera = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d right_from_left = Eigen::Isometry3d::Identity();
  SourceLocation where;  // of `sensor.cameras`
};

struct RobotSpec {
  double speed_mm_s = 6.0;             // descent speed
  double press_depth_mm = 1.5;         // further press after stable contact
  double safe_clearance_mm = 2.0;      // gel apex above the highest point under the gel
  double max_contact_depth_mm = 10.0;  // past first contact without stability: error
};

struct Scene {
  std::filesystem::path file;
  std::string name;
  ObjectSpec object;
  Workspace workspace{{-50, 50}, {-50, 50}, 10, 10};  // base frame; a scene usually sets it
  GelSpec gel;
  MarkerSpec markers;
  PlateSpec plate;
  CameraSpec cameras;
  double fps = 30.0;
  RobotSpec robot;
  EffectSet effects;
  EffectParameters effect_parameters;
  SourceLocation plate_where;  // of `sensor.plate`
};

// Default rig: two parallel cameras looking along +z_S, `baseline_mm` apart
// along x_S, `plate_gap_mm` below the plate's camera-side face.
inline constexpr double kDefaultBaselineMm = 30.0;
inline constexpr double kDefaultPlateGapMm = 45.0;

// Reads and checks a scene file. Throws InputError listing every problem,
// each naming the field ("sensor.plate.thickness_mm") and its place in the file.
Scene load_scene(const std::filesystem::path& file);

}  // namespace touchcloud::sim
