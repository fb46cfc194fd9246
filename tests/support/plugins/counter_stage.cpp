// Test plugin: counts calls, reads an optional number (for @previous wiring)
// and says when the count reaches `stop_at`.
#include <chrono>
#include <thread>

#include "touchcloud/plugin.hpp"

namespace {
class CounterStage final : public touchcloud::Stage {
  int stop_at_ = 0;
  double step_ = 1.0;
  std::vector<double> offsets_;
  bool flag_ = false;
  enum class Label { A, B };
  Label label_ = Label::A;
  int check_ms_ = 0;
  int record_only_at_call_ = 0;
  void declare_parameters(touchcloud::ParameterSet& p) override {
    p.add("stop_at", stop_at_, 0).at_least(0).unit("calls").doc("'done' turns true at this count (0: never)");
    p.add("step", step_, 1.0).range(-100.0, 100.0).doc("added to the previous value each call");
    p.add("offsets", offsets_, std::vector<double>{0, 0}).size(2).doc("two numbers");
    p.add("flag", flag_, false).doc("a switch");
    p.add("label", label_, Label::A, {{"a", Label::A}, {"b", Label::B}}).doc("a choice");
    p.add("check_ms", check_ms_, 0).at_least(0).unit("ms").doc("time its check hook takes (as a data file's loading)");
    p.add("record_only_at_call", record_only_at_call_, 0).at_least(0).unit("calls")
        .doc("produce 'record', when read only after the loop, at this call alone (0: on the call that ends the loop)");
  }
  void on_check(touchcloud::RunContext&) override {
    ++checks_;
    std::this_thread::sleep_for(std::chrono::milliseconds(check_ms_));
  }
  void declare_ports(touchcloud::PortSet& ports) override {
    ports.optional_input<double>("previous", "the value of an earlier call");
    ports.output<double>("value", "previous + step");
    ports.output<bool>("done", "count reached stop_at");
    ports.output<double>("record", "the value, as a simulator's costly image: made when read, or, when read only "
                                   "after the loop, on the call that ends it");
  }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext& ctx) override {
    const double* prev = io.optional_input<double>("previous");
    const double value = (prev ? *prev : 0.0) + step_;
    ++calls_;
    ctx.metric("value", value);
    io.output("value", value);
    // Only what some stage reads is worth computing.
    const bool done = stop_at_ > 0 && calls_ >= stop_at_;
    if (io.wants("done")) {
      ++done_computed_;
      io.output("done", done);
    }
    const bool ends_loop = record_only_at_call_ > 0 ? calls_ == record_only_at_call_ : done || io.final_call();
    if (io.wants("record") && (!io.wanted_after_loop_only("record") || ends_loop)) {
      ++record_computed_;
      io.output("record", value);
    }
  }
  void on_finish(touchcloud::RunContext& ctx) override {
    ctx.metric("calls", calls_, "calls");
    ctx.metric("checks", checks_, "calls");
    ctx.metric("done_computed", done_computed_, "calls");
    ctx.metric("record_computed", record_computed_, "calls");
    ctx.metric("random_draw", static_cast<double>(ctx.rng()() % 1000000));
  }
  int calls_ = 0, done_computed_ = 0, checks_ = 0, record_computed_ = 0;
};
}  // namespace

TOUCHCLOUD_PLUGIN(CounterStage, "test_counter", source, "Test only: counts its calls")
