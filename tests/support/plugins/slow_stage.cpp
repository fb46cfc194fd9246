// Test plugin: a stage that takes `sleep_ms` per call, so that a camera
// source's queue fills up behind it.
#include <chrono>
#include <thread>

#include "touchcloud/plugin.hpp"

namespace {
class SlowStage final : public touchcloud::Stage {
  int sleep_ms_ = 10;
  void declare_parameters(touchcloud::ParameterSet& p) override {
    p.add("sleep_ms", sleep_ms_, 10).at_least(0).unit("ms").doc("time each call takes");
  }
  void declare_ports(touchcloud::PortSet& ports) override {
    ports.optional_input<bool>("input", "anything, to place the stage after another");
  }
  void on_process(touchcloud::StageIO&, touchcloud::RunContext&) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(sleep_ms_));
  }
};
}  // namespace

TOUCHCLOUD_PLUGIN(SlowStage, "test_slow", source, "Test only: takes a while per call")
