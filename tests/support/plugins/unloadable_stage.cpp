// Test plugin: needs a function no library defines, so loading it fails.
#include "touchcloud/plugin.hpp"

extern "C" int touchcloud_symbol_that_does_not_exist();

namespace {
class UnloadableStage final : public touchcloud::Stage {
  void declare_ports(touchcloud::PortSet&) override {}
  void on_process(touchcloud::StageIO&, touchcloud::RunContext&) override { touchcloud_symbol_that_does_not_exist(); }
};
}  // namespace

TOUCHCLOUD_PLUGIN(UnloadableStage, "test_unloadable", geometry, "Test only: cannot be loaded")
