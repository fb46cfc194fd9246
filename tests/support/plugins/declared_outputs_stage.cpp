// Test plugin: declares a metric of each kind and an artifact role, and can
// be told to report or record what it did not declare.
#include <fstream>

#include "touchcloud/plugin.hpp"

namespace {
using namespace touchcloud;

class DeclaredOutputsStage final : public Stage {
  enum class Misreport { none, undeclared_metric, wrong_unit, undeclared_role, unwritten_file };
  Misreport misreport_ = Misreport::none;
  std::string file_ = "points.txt";

  void declare_parameters(ParameterSet& p) override {
    p.add("misreport", misreport_, Misreport::none,
          {{"none", Misreport::none},
           {"undeclared_metric", Misreport::undeclared_metric},
           {"wrong_unit", Misreport::wrong_unit},
           {"undeclared_role", Misreport::undeclared_role},
           {"unwritten_file", Misreport::unwritten_file}})
        .doc("what to get wrong on the first call");
    p.add("file", file_, std::string("points.txt")).output_file().doc("the table it writes at finish");
  }
  void declare_ports(PortSet& ports) override {
    ports.output<double>("value", "the call count");
    ports.metric("error_mm", "mm", "a made-up error, lower is better").lower_is_better().role(MetricRole::accuracy);
    ports.metric("calls", "calls", "how many calls there were").final();
    ports.artifact(ArtifactRole::table, "the call count, as text");
  }
  void on_process(StageIO& io, RunContext& ctx) override {
    ++calls_;
    switch (misreport_) {
      case Misreport::undeclared_metric: ctx.metric("surprise", 1.0); break;
      case Misreport::wrong_unit: ctx.metric("error_mm", 1.0, "px"); break;
      case Misreport::undeclared_role: ctx.artifact(ArtifactRole::image, ""); break;
      case Misreport::unwritten_file: ctx.artifact(ArtifactRole::table, "never_written.txt"); break;
      case Misreport::none: break;
    }
    ctx.metric("error_mm", 1.0 / calls_);
    io.output("value", static_cast<double>(calls_));
  }
  void on_finish(RunContext& ctx) override {
    ctx.metric("calls", calls_);
    std::ofstream(ctx.output_path(file_)) << calls_ << "\n";
    ctx.artifact(ArtifactRole::table, file_, {{"calls", std::int64_t{calls_}}});
  }
  int calls_ = 0;
};
}  // namespace

TOUCHCLOUD_PLUGIN(DeclaredOutputsStage, "test_declared_outputs", scoring,
                  "Test only: declares its metrics and artifacts")
