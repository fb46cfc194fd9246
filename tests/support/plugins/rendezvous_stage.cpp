// Test plugin: proves that a background stage overlaps the stages after it.
// Stages of this plugin share one counter (the library is loaded once): a
// `signal` stage counts its calls; a `wait` stage's n-th call waits until
// the signal count reaches n. Run in order on one thread, a waiting stage
// placed before its signal would wait for ever: it gives up after
// `timeout_ms` and fails the run instead.
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "touchcloud/plugin.hpp"

namespace {

std::mutex mutex;
std::condition_variable signalled;
int signals = 0;

class RendezvousStage final : public touchcloud::Stage {
  enum class Role { Signal, Wait };
  Role role_ = Role::Signal;
  int timeout_ms_ = 10000;
  int calls_ = 0;
  void declare_parameters(touchcloud::ParameterSet& p) override {
    p.add("role", role_, Role::Signal, {{"signal", Role::Signal}, {"wait", Role::Wait}}).doc("count calls, or wait for them");
    p.add("timeout_ms", timeout_ms_, 10000).at_least(1).unit("ms").doc("how long a wait may take");
  }
  void declare_ports(touchcloud::PortSet& ports) override { ports.output<double>("value", "calls so far"); }
  void on_configure(touchcloud::RunContext&) override {
    std::lock_guard<std::mutex> lock(mutex);
    if (role_ == Role::Signal) signals = 0;
  }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext&) override {
    ++calls_;
    std::unique_lock<std::mutex> lock(mutex);
    if (role_ == Role::Signal) {
      ++signals;
      signalled.notify_all();
    } else if (!signalled.wait_for(lock, std::chrono::milliseconds(timeout_ms_), [&] { return signals >= calls_; })) {
      throw std::runtime_error("no signal for call " + std::to_string(calls_) + " (the stages ran one after the other)");
    }
    io.output("value", static_cast<double>(calls_));
  }
};

}  // namespace

TOUCHCLOUD_PLUGIN(RendezvousStage, "test_rendezvous", geometry, "Test only: a stage that waits for the calls of another")
