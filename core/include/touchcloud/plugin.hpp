// The one entry point a plugin exports. Put this in one .cpp of the plugin:
//
//   TOUCHCLOUD_PLUGIN(VoxelDownsample, "downsample", geometry,
//                     "Down-samples a point cloud on a voxel grid or at random")
//
// The third argument is the plugin's category (PluginCategory), by which
// `touchcloud plugins` groups the list.
//
// The loader reads abi_version first and refuses the rest on a mismatch, so
// that field stays first whatever else changes.
#pragma once

#include <memory>
#include <string>

#include <boost/config.hpp>

#include "touchcloud/stage.hpp"
#include "touchcloud/version.hpp"

namespace touchcloud {

// What a plugin does in a chain, for grouping and finding plugins.
enum class PluginCategory {
  source,            // reads frames, images, clouds or datasets
  simulation,        // simulates a sensor and a robot
  image_to_markers,  // marker centres, matches and tracks from images
  geometry,          // clouds from markers or maps; cloud processing
  dense_depth,       // per-pixel disparity, depth or height, contact masks
  reconstruction,    // surfaces fitted to touches
  planning,          // where to touch next
  scoring,           // accuracy against ground truth
  calibration,       // sensor calibration from images or presses
  writer,            // files and pictures
  learning,          // network training and inference
};
inline constexpr PluginCategory kPluginCategories[] = {
    PluginCategory::source,      PluginCategory::simulation,  PluginCategory::image_to_markers,
    PluginCategory::geometry,    PluginCategory::dense_depth, PluginCategory::reconstruction,
    PluginCategory::planning,    PluginCategory::scoring,     PluginCategory::calibration,
    PluginCategory::writer,      PluginCategory::learning};
// "image_to_markers"; "" for a value outside the enum (a plugin's bug).
const char* to_string(PluginCategory category);
// "image to markers": as `touchcloud plugins` heads its groups.
std::string category_title(PluginCategory category);

struct PluginDescriptor {
  int abi_version;              // TOUCHCLOUD_PLUGIN_ABI_VERSION when built
  const char* toolkit_version;  // touchcloud version the plugin was built against
  const char* name;             // the name pipelines use
  PluginCategory category;
  const char* description;      // one line
  Stage* (*create)();           // a new, undeclared stage; the caller owns it
};

inline constexpr const char* kPluginEntryPoint = "touchcloud_plugin_descriptor";

}  // namespace touchcloud

#define TOUCHCLOUD_PLUGIN(STAGE_CLASS, NAME, CATEGORY, DESCRIPTION)                        \
  extern "C" BOOST_SYMBOL_EXPORT const ::touchcloud::PluginDescriptor*                    \
  touchcloud_plugin_descriptor() {                                                         \
    static const ::touchcloud::PluginDescriptor descriptor{                                \
        TOUCHCLOUD_PLUGIN_ABI_VERSION, TOUCHCLOUD_VERSION_STRING, NAME,                    \
        ::touchcloud::PluginCategory::CATEGORY, DESCRIPTION,                               \
        []() -> ::touchcloud::Stage* { return new STAGE_CLASS(); }};                       \
    return &descriptor;                                                                    \
  }
