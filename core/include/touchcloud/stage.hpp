// A stage is one plugin instance in a pipeline. The runtime owns the
// lifecycle through the public, non-virtual calls; a plugin implements only
// the private hooks it needs.
//
//   declare  -> parameters and ports, bound to members (once per instance)
//   check    -> cheap checks of external resources (files) for `validate`
//   configure-> once, after parameters are set, before the first item
//   process  -> once per item (per loop iteration inside a loop)
//   finish   -> once, after the last item: final metrics and files
#pragma once

#include "touchcloud/error.hpp"
#include "touchcloud/parameters.hpp"
#include "touchcloud/ports.hpp"
#include "touchcloud/run_context.hpp"

namespace touchcloud {

class Stage {
 public:
  virtual ~Stage() = default;

  void declare(ParameterSet& params, PortSet& ports);
  void check(RunContext& ctx) { on_check(ctx); }
  void configure(RunContext& ctx) { on_configure(ctx); }
  // Runs the hook, then insists every output that is read was produced.
  void process(StageIO& io, RunContext& ctx);
  void finish(RunContext& ctx) { on_finish(ctx); }

 private:
  virtual void declare_parameters(ParameterSet&) {}
  virtual void declare_ports(PortSet& ports) = 0;
  virtual void on_check(RunContext&) {}
  virtual void on_configure(RunContext&) {}
  virtual void on_process(StageIO& io, RunContext& ctx) = 0;
  virtual void on_finish(RunContext&) {}

  const PortSet* ports_ = nullptr;
};

}  // namespace touchcloud
