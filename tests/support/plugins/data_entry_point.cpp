// Test plugin: exports the descriptor itself (data) under the name of the
// entry function, so calling it would jump into data.
#include "touchcloud/plugin.hpp"

extern "C" BOOST_SYMBOL_EXPORT const touchcloud::PluginDescriptor touchcloud_plugin_descriptor{
    TOUCHCLOUD_PLUGIN_ABI_VERSION, TOUCHCLOUD_VERSION_STRING, "test_data_entry", touchcloud::PluginCategory::geometry, "Test only: descriptor as data",
    nullptr};
