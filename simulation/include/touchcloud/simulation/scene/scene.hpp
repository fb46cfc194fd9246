// A scene file: the object on the table, the sensor (gel, markers, plate,
// cameras), the robot's touch motion and the effects to simulate. Lengths in
// mm, angles in degrees. See sample_clouds/README.md for the format.
#pragma once

#include <array>
#include <optional>

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/simulation/scene/effects.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/sensor/gelsight_sensor.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/types/scene_object.hpp"
#include "touchcloud/types/workspace.hpp"

namespace touchcloud::simulation {

// The object on the table: sensing's scene object, shared with the chamfer
// stage's ground truth.
using touchcloud::ObjectKind;
using touchcloud::ObjectSpec;

// Where touches may go, and the paper's grid of sampling positions over it.
using Workspace = WorkspaceGrid;

struct RobotSpec {
  double speed_mm_s = 6.0;             // descent speed once the gel touches
  // Descent speed before the gel first touches (a guarded move: the robot
  // stops its fast approach on the first frame the sensor feels contact);
  // 0: speed_mm_s all the way.
  double approach_speed_mm_s = 0.0;
  double press_depth_mm = 1.5;         // further press after stable contact
  // Set: each touch's further press is drawn uniformly from [min, max] mm
  // instead (a dataset's presses of many depths), keyed by the seed and the
  // touch's number.
  std::optional<std::array<double, 2>> press_depth_range_mm;
  double safe_clearance_mm = 2.0;      // gel apex above the highest point under the gel
  double max_contact_depth_mm = 10.0;  // past first contact without stability: error
};

// A turntable under the object (`turntable:`): between touches it turns the
// object about the vertical axis through centre_mm. The object's own frame
// is the scene's base frame at angle 0: the simulator reports poses and
// points in it, so touches add up on the object and the scene's object stays
// the ground truth.
struct TurntableSpec {
  Eigen::Vector2d centre_mm = Eigen::Vector2d::Zero();
  std::vector<double> angles_deg;  // touch k at angles_deg[k], from the start again when touches outnumber them
  double step_deg = 0;             // without angles_deg: touch k at k * step_deg

  double angle_deg(int touch) const;
  // Where the object stands in the base frame during touch `touch`.
  Eigen::Isometry3d base_from_object(int touch) const;
};

struct Scene {
  std::filesystem::path file;
  std::string name;
  ObjectSpec object;
  Workspace workspace{{-50, 50}, {-50, 50}, 10, 10};  // base frame; a scene usually sets it
  // Which sensor the `sensor:` section describes (its `family` field; absent:
  // the GelStereo). Only the family's own description below is read.
  sensor::SensorFamily family = sensor::SensorFamily::GelStereo;
  sensor::GelStereoSensor sensor;  // the `sensor:` section (shared with the sensing stages)
  sensor::GelSightSensor gelsight; // the `sensor:` section of family gelsight
  RobotSpec robot;
  std::optional<TurntableSpec> turntable;  // not set: the object stands still on the table
  EffectSet effects;
  EffectParameters effect_parameters;

  // The camera frame rate of the family's sensor.
  double fps() const { return family == sensor::SensorFamily::GelSight ? gelsight.fps : sensor.fps; }
};

// Reads and checks a scene file. Throws InputError listing every problem,
// each naming the field ("sensor.plate.thickness_mm") and its place in the file.
Scene load_scene(const std::filesystem::path& file);

}  // namespace touchcloud::simulation
