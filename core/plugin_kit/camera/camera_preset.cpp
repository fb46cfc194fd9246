#include "touchcloud/plugin_kit/camera/camera_preset.hpp"

#include <cstdint>
#include <type_traits>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "touchcloud/error.hpp"
#include "touchcloud/run_context.hpp"

namespace touchcloud::camera {

namespace {

template <std::size_t N>
std::array<int, N> whole_numbers(const YAML::Node& node, const std::string& where) {
  if (!node.IsSequence() || node.size() != N)
    throw InputError(where + ": " + std::to_string(N) + " whole numbers expected");
  std::array<int, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = node[i].as<int>();
    if (out[i] < 0 || (i + 2 >= N && out[i] == 0)) throw InputError(where + ": sizes must be positive");
  }
  return out;
}

}  // namespace

CameraPreset read_camera_preset(const std::filesystem::path& file) {
  CameraPreset preset;
  const std::string name = file.string();
  try {
    const YAML::Node root = YAML::LoadFile(name);
    const YAML::Node camera = root["camera"];
    if (!camera || !camera.IsMap()) throw InputError(name + " has no 'camera:' section");
    for (const auto& entry : camera) {
      const std::string key = entry.first.as<std::string>();
      const std::string where = name + ":" + std::to_string(entry.second.Mark().line + 1) + ": camera." + key;
      if (key == "size") preset.size = whole_numbers<2>(entry.second, where);
      else if (key == "resize") preset.resize = whole_numbers<2>(entry.second, where);
      else if (key == "crop") preset.crop = whole_numbers<4>(entry.second, where);
      else if (key == "fps") {
        preset.fps = entry.second.as<double>();
        if (!(*preset.fps > 0)) throw InputError(where + ": frames per second must be positive");
      } else if (key == "pixel_format") {
        preset.pixel_format = entry.second.as<std::string>();
        if (preset.pixel_format->size() != 4) throw InputError(where + ": a FOURCC has four characters");
      } else {
        throw InputError(where + ": unknown key (size, fps, pixel_format, crop, resize)");
      }
    }
  } catch (const YAML::Exception& e) {
    throw InputError(name + " cannot be read: " + e.what());
  }
  return preset;
}

void fill_from_preset(CaptureSettings& s, const std::filesystem::path& file, RunContext* ctx) {
  const CameraPreset preset = read_camera_preset(file);
  const auto take = [&](auto& value, const auto& from_preset, const char* name) {
    if (value || !from_preset) return;
    value = from_preset;
    if (!ctx) return;
    using V = std::decay_t<decltype(*from_preset)>;
    if constexpr (std::is_same_v<V, double> || std::is_same_v<V, std::string>) ctx->used(name, *from_preset);
    else ctx->used(name, std::vector<std::int64_t>(from_preset->begin(), from_preset->end()));
  };
  take(s.size, preset.size, "size");
  take(s.fps, preset.fps, "fps");
  take(s.pixel_format, preset.pixel_format, "pixel_format");
  take(s.crop, preset.crop, "crop");
  take(s.resize, preset.resize, "resize");
}

}  // namespace touchcloud::camera
