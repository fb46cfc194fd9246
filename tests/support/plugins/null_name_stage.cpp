// Test plugin: a descriptor whose name is NULL.
#include "touchcloud/plugin.hpp"

namespace {
class NullNameStage final : public touchcloud::Stage {
  void declare_ports(touchcloud::PortSet&) override {}
  void on_process(touchcloud::StageIO&, touchcloud::RunContext&) override {}
};
}  // namespace

extern "C" BOOST_SYMBOL_EXPORT const touchcloud::PluginDescriptor* touchcloud_plugin_descriptor() {
  static const touchcloud::PluginDescriptor descriptor{
      TOUCHCLOUD_PLUGIN_ABI_VERSION, TOUCHCLOUD_VERSION_STRING, nullptr, touchcloud::PluginCategory::geometry, "Test only: no name",
      []() -> touchcloud::Stage* { return new NullNameStage(); }};
  return &descriptor;
}
