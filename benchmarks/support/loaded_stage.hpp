// A plugin's stage loaded by name, checked and configured, driven one frame
// at a time as the runtime does: what the per-frame benchmarks time.
#pragma once

#include <any>
#include <map>
#include <memory>
#include <string>

#include "touchcloud/plugin_registry.hpp"
#include "touchcloud/run_context.hpp"
#include "touchcloud/stage.hpp"

namespace touchcloud::bench {

class LoadedStage {
 public:
  LoadedStage(const std::string& plugin, const std::map<std::string, ParamValue>& params)
      : stage_(registry().load(plugin).create()), ctx_(plugin, 1, record_) {
    stage_->declare(params_, ports_);
    for (const auto& [name, value] : params) params_.assign(name, value);
    stage_->check(ctx_);
    stage_->configure(ctx_);
  }
  std::any run(std::map<std::string, std::any> inputs, const std::string& output) {
    StageIO io(ports_, std::move(inputs), {output});
    stage_->process(io, ctx_);
    record_.metrics.clear();  // per-frame metrics would pile up over millions of frames
    return io.outputs().at(output);
  }

 private:
  static PluginRegistry& registry() {
    static PluginRegistry r;
    return r;
  }
  std::unique_ptr<Stage> stage_;
  ParameterSet params_;
  PortSet ports_;
  RunRecord record_;
  RunContext ctx_;
};

}  // namespace touchcloud::bench
