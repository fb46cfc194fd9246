// A true GelStereo sensor that differs from the nominal one as a real build
// would (plate tilted [1.5, -2] deg, cameras 1 mm closer, mu_silicone 1.45),
// and checkerboard presses simulated through it.
#pragma once

#include <random>
#include <vector>

#include "test_support.hpp"
#include "touchcloud/calibration/press_corners.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/simulation/board/board_press.hpp"

namespace touchcloud::test {

inline sensor::GelStereoSensor nominal_sensor() {
  return sensor::load_gelstereo_sensor(source_dir() / "sample_clouds/fox_mask/scene.yaml");
}

inline sensor::GelStereoSensor true_sensor() {
  sensor::GelStereoSensor s = nominal_sensor();
  s.plate.tilt_deg = {1.5, -2.0};
  s.plate.mu_silicone = 1.45;
  s.cameras.housing_from_left_camera.translation().z() += 1.0;  // gap 44 mm instead of 45
  return s;
}

inline const calibration::Checkerboard kBoard{8, 6, 4.0};

// Presses of kBoard into `truth`'s gel, imaged with `noise_px`.
inline std::vector<calibration::PressCorners> simulate_presses(const sensor::GelStereoSensor& truth,
                                                               const std::vector<simulation::BoardPose>& poses,
                                                               double noise_px, std::mt19937_64& rng) {
  const auto rig = sensor::make_stereo_rig(truth, true, true);
  const Eigen::Isometry3d left_from_sensor = truth.sensor_from_left_camera().inverse();
  std::vector<calibration::PressCorners> presses;
  for (const auto& pose : poses) {
    const auto corners = simulation::board_corners_sensor(kBoard, pose, truth.gel.radius_mm());
    const auto set = simulation::image_press(rig, left_from_sensor, corners, truth.gel.radius_mm(),
                                              {noise_px, 0.5}, rng);
    presses.push_back(calibration::press_corners_from(*set, kBoard, "test press"));
  }
  return presses;
}

inline std::vector<simulation::BoardPose> flat_poses(int count) {
  std::vector<simulation::BoardPose> poses(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    poses[static_cast<std::size_t>(i)].depth_mm = 4.0 + i;
    poses[static_cast<std::size_t>(i)].spin_deg = 10.0 * i;
  }
  return poses;
}

}  // namespace touchcloud::test
