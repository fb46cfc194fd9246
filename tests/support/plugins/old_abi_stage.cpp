// Test plugin: claims a plugin ABI one older than the toolkit's.
#include "touchcloud/plugin.hpp"

#undef TOUCHCLOUD_PLUGIN_ABI_VERSION
#define TOUCHCLOUD_PLUGIN_ABI_VERSION 0

namespace {
class OldStage final : public touchcloud::Stage {
  void declare_ports(touchcloud::PortSet&) override {}
  void on_process(touchcloud::StageIO&, touchcloud::RunContext&) override {}
};
}  // namespace

TOUCHCLOUD_PLUGIN(OldStage, "test_old_abi", geometry, "Test only: built for another ABI")
