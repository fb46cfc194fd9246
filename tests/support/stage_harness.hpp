// Drives one plugin's stage by hand, outside a pipeline: set parameters,
// configure, feed inputs item by item, finish, and read metrics.
#pragma once

#include <any>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "test_support.hpp"
#include "touchcloud/run_context.hpp"
#include "touchcloud/stage.hpp"

namespace touchcloud::test {

class StageHarness {
 public:
  // Loads `plugin` (search path plus the test plugins) and sets `params`
  // (absolute paths for files); does not configure yet. `settings` gives a
  // writer its staging folder.
  StageHarness(const std::string& plugin, const std::map<std::string, ParamValue>& params,
               const std::string& stage_id = "stage", RunSettings settings = {})
      : registry_(test_registry()), stage_(registry_.load(plugin).create()), ctx_(stage_id, 0, record_, settings) {
    stage_->declare(params_, ports_);
    for (const auto& [name, value] : params) params_.assign(name, value);
  }

  void configure() { stage_->configure(ctx_); }

  // One item: `inputs` by port name; returns the outputs asked for.
  std::map<std::string, std::any> process(std::map<std::string, std::any> inputs, std::set<std::string> wanted) {
    StageIO io(ports_, std::move(inputs), std::move(wanted));
    stage_->process(io, ctx_);
    return io.outputs();
  }
  template <class T>
  T process_one(std::map<std::string, std::any> inputs, const std::string& output) {
    return std::any_cast<T>(process(std::move(inputs), {output}).at(output));
  }

  void finish() { stage_->finish(ctx_); }
  const RunRecord& record() const { return record_; }
  // The last value of this stage's metric `name`.
  double metric(const std::string& name) const { return record_.metrics.at(ctx_key(name)).values.back(); }

 private:
  std::string ctx_key(const std::string& name) const { return ctx_.stage_id() + "." + name; }

  PluginRegistry registry_;
  std::unique_ptr<Stage> stage_;
  ParameterSet params_;
  PortSet ports_;
  RunRecord record_;
  RunContext ctx_;
};

}  // namespace touchcloud::test
