// The one entry point a plugin exports. Put this in one .cpp of the plugin:
//
//   TOUCHCLOUD_PLUGIN(VoxelDownsample, "downsample",
//                     "Down-samples a point cloud on a voxel grid or at random")
//
// The loader reads abi_version first and refuses the rest on a mismatch, so
// that field stays first whatever else changes.
#pragma once

#include <memory>

#include <boost/config.hpp>

#include "touchcloud/stage.hpp"
#include "touchcloud/version.hpp"

namespace touchcloud {

struct PluginDescriptor {
  int abi_version;              // TOUCHCLOUD_PLUGIN_ABI_VERSION when built
  const char* toolkit_version;  // touchcloud version the plugin was built against
  const char* name;             // the name pipelines use
  const char* description;      // one line
  Stage* (*create)();           // a new, undeclared stage; the caller owns it
};

inline constexpr const char* kPluginEntryPoint = "touchcloud_plugin_descriptor";

}  // namespace touchcloud

#define TOUCHCLOUD_PLUGIN(STAGE_CLASS, NAME, DESCRIPTION)                                  \
  extern "C" BOOST_SYMBOL_EXPORT const ::touchcloud::PluginDescriptor*                    \
  touchcloud_plugin_descriptor() {                                                         \
    static const ::touchcloud::PluginDescriptor descriptor{                                \
        TOUCHCLOUD_PLUGIN_ABI_VERSION, TOUCHCLOUD_VERSION_STRING, NAME, DESCRIPTION,       \
        []() -> ::touchcloud::Stage* { return new STAGE_CLASS(); }};                       \
    return &descriptor;                                                                    \
  }
