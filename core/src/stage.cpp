#include "touchcloud/stage.hpp"

namespace touchcloud {

void Stage::declare(ParameterSet& params, PortSet& ports) {
  declare_parameters(params);
  declare_ports(ports);
  ports_ = &ports;
}

void Stage::process(StageIO& io, RunContext& ctx) {
  on_process(io, ctx);
  if (!ports_) return;
  for (const auto& out : ports_->outputs())
    if (io.wants(out.name) && !io.outputs().count(out.name))
      throw RunError("the stage did not produce its output '" + out.name + "'");
}

}  // namespace touchcloud
