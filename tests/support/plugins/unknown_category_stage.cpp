// Test plugin: a descriptor whose category is none of PluginCategory's.
#include "touchcloud/plugin.hpp"

namespace {
class UnknownCategoryStage final : public touchcloud::Stage {
  void declare_ports(touchcloud::PortSet&) override {}
  void on_process(touchcloud::StageIO&, touchcloud::RunContext&) override {}
};
}  // namespace

extern "C" BOOST_SYMBOL_EXPORT const touchcloud::PluginDescriptor* touchcloud_plugin_descriptor() {
  static const touchcloud::PluginDescriptor descriptor{
      TOUCHCLOUD_PLUGIN_ABI_VERSION, TOUCHCLOUD_VERSION_STRING, "test_unknown_category",
      static_cast<touchcloud::PluginCategory>(99), "Test only: a category outside the enum",
      []() -> touchcloud::Stage* { return new UnknownCategoryStage(); }};
  return &descriptor;
}
