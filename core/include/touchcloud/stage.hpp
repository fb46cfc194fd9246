// A stage is one plugin instance in a pipeline. The runtime owns the
// lifecycle through the public, non-virtual calls; a plugin implements only
// the private hooks it needs, and never calls one hook from another.
//
// The order, enforced here for the runtime and the test harness alike:
//   declare   -> parameters and ports, bound to members (once per instance);
//                every default is checked against its own rule
//   (the runtime or harness sets parameters)
//   check     -> the rules between parameters, then on_check: cheap checks
//                of external resources (files) for `validate`. State found
//                here (a file read, a scene parsed) is kept for configure
//   configure -> once, before the first item; runs check first if it has
//                not run
//   process   -> once per item (per loop iteration inside a loop); only
//                after configure
//   finish    -> once, after the last item: final metrics and files
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
  // ParameterError for the first broken rule between parameters.
  void check(RunContext& ctx);
  void configure(RunContext& ctx);
  // Runs the hook, then insists every output that is read was produced.
  void process(StageIO& io, RunContext& ctx);
  void finish(RunContext& ctx);

 private:
  virtual void declare_parameters(ParameterSet&) {}
  virtual void declare_ports(PortSet& ports) = 0;
  virtual void on_check(RunContext&) {}
  virtual void on_configure(RunContext&) {}
  virtual void on_process(StageIO& io, RunContext& ctx) = 0;
  virtual void on_finish(RunContext&) {}

  const ParameterSet* params_ = nullptr;
  const PortSet* ports_ = nullptr;
  bool checked_ = false, configured_ = false;
};

}  // namespace touchcloud
