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

#include "touchcloud/plugin_kit/camera/capture.hpp"

namespace touchcloud {
class RunContext;
}

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

// What `settings` leaves unset (size, fps, pixel_format, crop, resize) taken
// from the sensor file's camera: section; each value taken is recorded as
// used when `ctx` is given. InputError as read_camera_preset.
void fill_from_preset(CaptureSettings& settings, const std::filesystem::path& file, RunContext* ctx);

}  // namespace touchcloud::camera
