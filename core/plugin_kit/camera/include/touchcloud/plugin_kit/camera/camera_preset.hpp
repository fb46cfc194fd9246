// The `camera:` section of a sensor file (sample_clouds/sensors/*.yaml):
// how the sensor's camera delivers frames. A stage's own parameters
// override it.
//
//   camera:
//     size: [320, 240]      # width, height delivered, px
//     fps: 25
//     pixel_format: MJPG    # FOURCC
//     crop: [x, y, width, height]
//     resize: [width, height]
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

namespace touchcloud::camera {

struct CameraPreset {
  std::optional<std::array<int, 2>> size, resize;
  std::optional<double> fps;
  std::optional<std::string> pixel_format;
  std::optional<std::array<int, 4>> crop;
};

// InputError naming the file and key for a missing section, an unknown key
// or a malformed value.
CameraPreset read_camera_preset(const std::filesystem::path& file);

}  // namespace touchcloud::camera
