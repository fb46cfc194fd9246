// Test plugin: throws from process on the iteration named by `fail_at`.
// Under mpirun, TOUCHCLOUD_TEST_KILL_RANK=N kills rank N outright (SIGKILL)
// in its first call: a rank that dies.
#include <csignal>
#include <cstdlib>
#include <string>

#include "touchcloud/error.hpp"
#include "touchcloud/plugin.hpp"

namespace {
class ThrowingStage final : public touchcloud::Stage {
  int fail_at_ = 0;
  void declare_parameters(touchcloud::ParameterSet& p) override {
    p.add("fail_at", fail_at_, 0).at_least(0).doc("call index that throws");
    p.add("skip_output", skip_output_, false).doc("return without producing 'value'");
    p.add("error", error_, Kind::Runtime, {{"runtime", Kind::Runtime}, {"input", Kind::Input}, {"run", Kind::Run}})
        .doc("what it throws: std::runtime_error, touchcloud::InputError or touchcloud::RunError");
  }
  void declare_ports(touchcloud::PortSet& ports) override { ports.output<double>("value", "the call index"); }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext&) override {
    const char* kill = std::getenv("TOUCHCLOUD_TEST_KILL_RANK");
    const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (kill && rank && std::string(kill) == rank) std::raise(SIGKILL);
    if (calls_ == fail_at_) {
      const std::string what = "the gel tore (simulated failure)";
      if (error_ == Kind::Input) throw touchcloud::InputError(what);
      if (error_ == Kind::Run) throw touchcloud::RunError(what);
      throw std::runtime_error(what);
    }
    if (skip_output_) return;
    io.output("value", static_cast<double>(calls_++));
  }
  int calls_ = 0;
  bool skip_output_ = false;
  enum class Kind { Runtime, Input, Run };
  Kind error_ = Kind::Runtime;
};
}  // namespace

TOUCHCLOUD_PLUGIN(ThrowingStage, "test_throwing", geometry, "Test only: throws on a chosen call")
