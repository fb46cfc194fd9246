// Test plugin: its create() returns NULL instead of a stage.
#include "touchcloud/plugin.hpp"

extern "C" BOOST_SYMBOL_EXPORT const touchcloud::PluginDescriptor* touchcloud_plugin_descriptor() {
  static const touchcloud::PluginDescriptor descriptor{
      TOUCHCLOUD_PLUGIN_ABI_VERSION, TOUCHCLOUD_VERSION_STRING, "test_null_stage", touchcloud::PluginCategory::geometry, "Test only: creates no stage",
      []() -> touchcloud::Stage* { return nullptr; }};
  return &descriptor;
}
