#include "touchcloud/stage.hpp"

#include <stdexcept>

namespace touchcloud {

void Stage::declare(ParameterSet& params, PortSet& ports) {
  declare_parameters(params);
  params.check_defaults();
  declare_ports(ports);
  params_ = &params;
  ports_ = &ports;
}

void Stage::check(RunContext& ctx) {
  ctx.bind_declarations(ports_);
  if (params_)
    for (const auto& [name, why] : params_->broken_rules()) throw ParameterError(name, why);
  on_check(ctx);
  checked_ = true;
}

void Stage::configure(RunContext& ctx) {
  if (!checked_) check(ctx);
  ctx.bind_declarations(ports_);
  on_configure(ctx);
  configured_ = true;
}

void Stage::process(StageIO& io, RunContext& ctx) {
  if (!configured_) throw std::logic_error("stage '" + ctx.stage_id() + "' processed before it was configured");
  ctx.bind_declarations(ports_);
  on_process(io, ctx);
  if (!ports_) return;
  for (const auto& out : ports_->outputs())
    if (io.wants(out.name) && !io.outputs().count(out.name) && !io.wanted_after_loop_only(out.name))
      throw RunError("the stage did not produce its output '" + out.name + "'");
}

void Stage::finish(RunContext& ctx) {
  if (!configured_) throw std::logic_error("stage '" + ctx.stage_id() + "' finished before it was configured");
  ctx.bind_declarations(ports_);
  on_finish(ctx);
}

}  // namespace touchcloud
