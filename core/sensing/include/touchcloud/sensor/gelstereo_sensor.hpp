// The GelStereo Palm 2.0 as a description file gives it: gel, markers,
// acrylic plate and stereo cameras. The simulator, the sensing stages
// (marker matching, RSRT triangulation) and refractive calibration all read
// the same `sensor:` section, from a scene file or from a sensor file that
// calibration writes. Lengths in mm, angles in degrees.
//
// Frames: the sensor frame {S} has its origin on the plate's gel-side face,
// z along the plate normal into the gel. The cameras are mounted in the
// housing; the plate (with the gel) is turned relative to the housing by
// `plate.tilt_deg` about the housing's x and y axes — what calibration
// estimates.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <Eigen/Geometry>

#include "touchcloud/config/yaml_fields.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/optics/pinhole_camera.hpp"
#include "touchcloud/optics/refractive_plate.hpp"
#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::sensor {

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

// What is printed on the gel's surface: marker dots (the Palm 2.0), or a
// dense, semitransparent colour pattern (the colour-pattern GelStereo, seed
// 000's water-transfer layer) for dense stereo.
enum class GelPattern { Markers, ColourPattern };

struct ColourPatternSpec {
  double feature_mm = 0.6;   // size of the pattern's colour blobs on the gel
  double opacity = 0.8;      // share of the pattern's colour over the white gel (semitransparent)
  std::uint64_t seed = 1;    // the pattern is a property of the gel, not of a run
  double vignetting = 0.1;   // the LED ring's light: uniform, this much darker at the corners
  int width_px = 0, height_px = 0;  // size of the rectified images (0: the left camera's)
  double surface_grid_mm = 0.2;     // spacing of the dense gel surface that deforms
};

struct PlateSpec {
  double thickness_mm = 5.0;
  Eigen::Vector2d tilt_deg = Eigen::Vector2d::Zero();  // about the housing's x, then y axis
  double mu_air = 1.0, mu_acrylic = 1.49, mu_silicone = 1.41;
};

struct CameraSpec {
  optics::CameraIntrinsics left, right;  // distortion used only where lens distortion is modelled
  // Pose of the left camera (OpenCV axes) in the housing, i.e. in the sensor
  // frame before the plate's tilt; the right camera relative to the left.
  Eigen::Isometry3d housing_from_left_camera = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d right_from_left = Eigen::Isometry3d::Identity();
};

// Default rig: two parallel cameras looking along +z, `baseline_mm` apart
// along x, `plate_gap_mm` below the plate's camera-side face.
inline constexpr double kDefaultBaselineMm = 30.0;
inline constexpr double kDefaultPlateGapMm = 45.0;

struct GelStereoSensor {
  GelSpec gel;
  MarkerSpec markers;
  GelPattern pattern = GelPattern::Markers;
  ColourPatternSpec colour_pattern;  // used with GelPattern::ColourPattern
  PlateSpec plate;
  CameraSpec cameras;
  double fps = 30.0;
  std::filesystem::path file;              // where it was read, if from a file
  SourceLocation cameras_where, plate_where;  // of `sensor.cameras`, `sensor.plate`, for later errors

  // The left camera in the sensor frame, the plate's tilt included.
  Eigen::Isometry3d sensor_from_left_camera() const;
};

// Reads the fields of a `sensor:` mapping into `sensor` (defaults stay where
// a field is absent); problems go to `problems`.
void read_gelstereo_sensor(config::ConfigFields& fields, config::ConfigProblems& problems, GelStereoSensor& sensor);

// The `sensor:` section of a scene file or sensor file (other top-level keys
// are left to their readers). InputError listing every problem, each naming
// its field and place; a file without a `sensor:` section is an error.
GelStereoSensor load_gelstereo_sensor(const std::filesystem::path& file);

// The sensor file a stage parameter names, checked by building the rig as
// make_stereo_rig would; any problem is a ParameterError naming `parameter`.
GelStereoSensor load_sensor_parameter(const std::string& file, const std::string& parameter, bool refraction,
                                      bool lens_distortion);

// The two cameras and the plate in the left camera frame. Without
// `refraction` the plate has equal indices (straight rays: the pinhole
// model); without `lens_distortion` the distortion coefficients are ignored.
// InputError naming sensor.cameras when cameras and plate do not fit.
optics::StereoRig make_stereo_rig(const GelStereoSensor& sensor, bool refraction, bool lens_distortion);

// Changes the plate's tilt, indices and the left camera's distance to it so
// that make_stereo_rig(...).plate() becomes `plate_left` (a plate in the left
// camera frame, as calibration estimates it). The thickness is kept.
void set_plate_from_left_frame(GelStereoSensor& sensor, const optics::RefractivePlate& plate_left);

// Writes a sensor file (`sensor:` section only) that load_gelstereo_sensor
// reads back to the same rig; `comment` lines go at the top. Writes to a
// temporary name and renames; InputError when the folder is not writable.
void write_gelstereo_sensor(const GelStereoSensor& sensor, const std::filesystem::path& file,
                            const std::string& comment);

}  // namespace touchcloud::sensor
