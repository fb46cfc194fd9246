// Runs a resolved pipeline: configure every stage, run the nodes (loops
// iterate up to their budget), finish, then publish outputs atomically.
// Background stages get their calls (configure included) queued to one
// worker thread; their outputs are futures, which a reader waits for.

#include <algorithm>
#include <chrono>
#include <limits>
#include <future>
#include <optional>

#include "background_worker.hpp"
#include "output_staging.hpp"
#include "pipeline_model.hpp"
#include "run_summary.hpp"
#include "touchcloud/file_write.hpp"
#include "touchcloud/stream.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A stage output as the runner holds it: the value, or, from a background
// stage, the outputs of the call that computes it (which may still run).
struct Value {
  using Outputs = std::map<std::string, std::any>;
  std::any ready;
  std::shared_future<Outputs> pending;  // valid: from a background stage
  std::string port;                     // of `pending`
};
using Values = std::unordered_map<std::string, Value>;

// The value, waiting for a background call if need be (and rethrowing its
// error); none when the call did not produce it.
std::optional<std::any> resolve(const Value& v) {
  if (!v.pending.valid()) return v.ready;
  const Value::Outputs& outputs = v.pending.get();
  if (auto it = outputs.find(v.port); it != outputs.end()) return it->second;
  return std::nullopt;
}

class Runner {
 public:
  Runner(ResolvedPipeline& p, const RunOptions& o, const StreamOptions* stream)
      : pipeline_(p), options_(o), stream_(stream), capture_(o.capture) {}

  RunResult run() {
    const auto t0 = Clock::now();
    OutputStaging staging(options_.out_dir);
    RunRecord& record = pipeline_.record;
    record = RunRecord{};
    want_captured_outputs();
    const RunSettings settings{staging.dir(), options_.quiet, options_.log_sink, options_.on_stage_progress};
    for (auto* s : pipeline_.stages) {
      s->context = std::make_unique<RunContext>(s->id, options_.seed, record, settings);
      s->timing = {s->id, s->plugin->name(), s->timing.check_s};  // the load's check time stays
      s->iteration = -1;
      s->call_s.clear();
    }
    for (auto* s : pipeline_.stages) {
      const auto configure = [this, s] { timed(*s, "configure", s->timing.configure_s, [&] { s->stage->configure(*s->context); }); };
      if (!s->background) {
        configure();
        continue;
      }
      worker_.submit([configure](std::exception_ptr earlier) {
        if (!earlier) configure();
      });
    }
    run_nodes(pipeline_.nodes);
    worker_.wait_idle();
    rethrow_background_error();
    for (auto* s : pipeline_.stages) timed(*s, "finish", s->timing.finish_s, [&] { s->stage->finish(*s->context); });

    RunResult result;
    result.record = record;
    for (auto* s : pipeline_.stages) result.timings.push_back(s->timing);
    for (auto* l : pipeline_.loops) result.loop_iterations.emplace_back(l->id, l->iterations_run);
    result.wall_time_s = seconds_since(t0);
    result.load_time_s = pipeline_.load_time_s;
    result.captured = captured();
    for (const auto& [key, calls] : every_call_)
      for (const auto& call : calls)
        if (std::optional<std::any> v = resolve(call); v && v->has_value()) result.captured_every_call[key].push_back(std::move(*v));
    result.summary_json = make_summary(pipeline_, result, options_).dump(2) + "\n";
    if (!options_.out_dir.empty()) {
      auto files = record.outputs;
      write_file(staging.dir() / "summary.json", result.summary_json);
      files.push_back("summary.json");
      staging.commit(files);
    }
    return result;
  }

 private:
  // RunOptions::capture's outputs as they stand (waiting for background calls).
  std::map<std::string, std::any> captured() const {
    std::map<std::string, std::any> out;
    for (const auto& key : capture_)
      if (auto it = values_.find(key); it != values_.end())
        if (std::optional<std::any> v = resolve(it->second); v && v->has_value()) out[key] = std::move(*v);
    return out;
  }

  // RunOptions::capture (and, streaming, the outputs of capture_types):
  // known outputs, produced as if a stage read them.
  void want_captured_outputs() {
    if (stream_)
      for (auto* s : pipeline_.stages)
        for (const auto& out : s->ports->outputs())
          if (std::count(stream_->capture_types.begin(), stream_->capture_types.end(), out.type))
            capture_.push_back(s->id + "." + out.name);
    captured_ = {options_.capture.begin(), options_.capture.end()};
    capture_keys_ = {capture_.begin(), capture_.end()};
    for (const auto& key : capture_) {
      const auto dot = key.rfind('.');
      const std::string id = key.substr(0, dot), port = dot == std::string::npos ? "" : key.substr(dot + 1);
      const auto stage = std::find_if(pipeline_.stages.begin(), pipeline_.stages.end(), [&](auto* s) { return s->id == id; });
      if (stage == pipeline_.stages.end()) throw InputError("capture '" + key + "': the pipeline has no stage '" + id + "'");
      if (!(*stage)->ports->find_output(port)) {
        std::string names;
        for (const auto& o : (*stage)->ports->outputs()) names += (names.empty() ? "" : ", ") + o.name;
        throw InputError("capture '" + key + "': stage '" + id + "' has no output '" + port + "' (its outputs: " +
                         (names.empty() ? "none" : names) + ")");
      }
      (*stage)->wanted_outputs.insert(port);
      // Every call's value is handed back when each call's is kept, or each
      // frame's when streaming; otherwise the last alone, as a stage after
      // the loop reads it, so a simulator renders only the frame that ends
      // a touch.
      if (options_.capture_every_call || stream_) (*stage)->read_in_loop.insert(port);
    }
  }

  void run_nodes(std::vector<ResolvedNode>& nodes) {
    for (auto& n : nodes) run_node(n);
  }
  void run_node(ResolvedNode& n) {
    if (n.stage) run_stage(*n.stage);
    else run_loop(*n.loop);
  }

  // Each output read from the loop's previous iteration (`stage.port@previous`),
  // with the last node of the loop's body that reads it (a nested loop
  // counts as one node).
  static std::map<std::string, std::size_t> last_previous_readers(const ResolvedLoop& loop) {
    std::map<std::string, std::size_t> last;
    for (std::size_t n = 0; n < loop.body.size(); ++n) {
      const ResolvedNode& node = loop.body[n];
      std::vector<const ResolvedStage*> stages;
      if (node.stage) stages.push_back(node.stage.get());
      else stages.assign(node.loop->stages.begin(), node.loop->stages.end());
      for (const ResolvedStage* s : stages)
        for (const auto& in : s->inputs)
          if (in.previous_of == &loop) last[in.key] = n;
    }
    return last;
  }

  int loop_depth_ = 0;  // of the loop running now: 1 for a top-level one

  void run_loop(ResolvedLoop& loop) {
    loop.iterations_run = 0;
    auto& previous = previous_[&loop];
    previous.clear();
    // Outputs read only after this loop may be skipped on all but its last
    // call: a value from an earlier run of the loop must not stand in for it.
    for (auto* s : loop.stages)
      if (!s->loops.empty() && s->loops.back() == &loop)
        for (const auto& port : after_loop_outputs(*s)) values_.erase(s->id + "." + port);
    const std::int64_t budget = this->budget(loop);
    const std::map<std::string, std::size_t> last_reader = last_previous_readers(loop);
    for (std::int64_t i = 0; i < budget; ++i) {
      if (i > 0) {
        previous.clear();
        for (const auto& [key, node] : last_reader)
          if (auto it = values_.find(key); it != values_.end()) previous[key] = it->second;
      }
      for (auto* s : loop.stages) s->iteration = static_cast<int>(i);
      ++loop_depth_;
      for (std::size_t n = 0; n < loop.body.size(); ++n) {
        run_node(loop.body[n]);
        // Let go of what no later node of this iteration reads: a stage
        // that updates a model in place then need not copy it.
        for (const auto& [key, node] : last_reader)
          if (node == n) previous.erase(key);
      }
      --loop_depth_;
      ++loop.iterations_run;
      if (loop_depth_ == 0 && options_.on_loop_iteration)
        options_.on_loop_iteration(loop.id, loop.iterations_run, budget);
      if (loop_depth_ == 0 && stream_ && stream_->on_frame) stream_->on_frame(i, captured(), pipeline_.record);
      if (loop.until_key) {
        const std::optional<std::any> until = resolve(values_.at(*loop.until_key));
        if (until && std::any_cast<bool>(*until)) break;
      }
      if (loop_depth_ == 0 && stream_ && stream_->stop && stream_->stop->load()) break;
    }
  }

  // A loop's iterations: its max_iterations, or when streaming a top-level
  // loop's frame count (none: until it ends or is stopped).
  std::int64_t budget(const ResolvedLoop& loop) const {
    if (!stream_) return loop.max_iterations;
    for (const auto& n : pipeline_.nodes)
      if (n.loop.get() == &loop) return stream_->frames.value_or(std::numeric_limits<std::int64_t>::max());
    return loop.max_iterations;
  }

  void run_stage(ResolvedStage& s) {
    // Inputs are gathered now, in the runner's order; a background call
    // resolves them when it starts (those from background stages are ready
    // by then: their calls came first).
    std::vector<std::pair<std::string, Value>> inputs;
    for (const auto& in : s.inputs) {
      const auto& source = in.previous_of ? previous_[in.previous_of] : values_;
      if (auto it = source.find(in.key); it != source.end()) {
        inputs.emplace_back(in.port, it->second);
      } else if (!in.previous_of) {  // wired, and not from an iteration yet to come
        s.context->set_iteration(s.iteration);
        timed(s, "process", s.timing.process_s, [&] {
          throw RunError("input '" + in.port + "' has no value: " + in.key +
                         " was not produced (its stage produces it only on the call that ends its loop, and the "
                         "loop ended without it)");
        });
      }
    }
    if (s.background) {
      submit_background(s, std::move(inputs));
      return;
    }
    s.context->set_iteration(s.iteration);
    // The last call's outputs go first: Stage::process makes every output
    // read in the loop be produced again (or fails), so no reader needs them,
    // and a stage that updates a model it hands out (gpis_surface) then holds
    // the only reference and need not copy it. Those read only after the
    // loop stay: a call may skip them. So do captured ones: the live view
    // tells a new value by its address, which a freed one could pass on.
    const std::set<std::string> after_loop = after_loop_outputs(s);
    for (const auto& out : s.ports->outputs())
      if (const std::string key = s.id + "." + out.name; !after_loop.count(out.name) && !capture_keys_.count(key))
        values_.erase(key);
    Value::Outputs outputs = process(s, inputs);
    for (auto& [port, value] : outputs) {
      Value& kept = values_[s.id + "." + port] = {std::move(value), {}, {}};
      keep_call(s.id + "." + port, kept);
    }
  }

  // RunOptions::capture_every_call: each call's value of a captured output.
  void keep_call(const std::string& key, const Value& value) {
    if (options_.capture_every_call && captured_.count(key)) every_call_[key].push_back(value);
  }

  // One call of the process hook, on whichever thread runs it.
  Value::Outputs process(ResolvedStage& s, const std::vector<std::pair<std::string, Value>>& inputs) {
    std::map<std::string, std::any> resolved;
    for (const auto& [port, value] : inputs)
      if (auto v = resolve(value)) resolved[port] = std::move(*v);
    const bool final_call = s.loops.empty() || s.iteration == budget(*s.loops.back()) - 1;
    StageIO io(*s.ports, std::move(resolved), s.wanted_outputs, after_loop_outputs(s), final_call);
    const double before_s = s.timing.process_s;
    timed(s, "process", s.timing.process_s, [&] { s.stage->process(io, *s.context); });
    ++s.timing.calls;
    if (stream_) s.call_s.push_back(s.timing.process_s - before_s);
    return std::move(io.outputs());
  }

  // The stage's outputs read only after its innermost loop.
  static std::set<std::string> after_loop_outputs(const ResolvedStage& s) {
    std::set<std::string> out;
    if (s.loops.empty()) return out;
    for (const auto& port : s.wanted_outputs)
      if (!s.read_in_loop.count(port)) out.insert(port);
    return out;
  }

  void submit_background(ResolvedStage& s, std::vector<std::pair<std::string, Value>> inputs) {
    rethrow_background_error();  // stop soon after a background call fails
    auto promise = std::make_shared<std::promise<Value::Outputs>>();
    const std::shared_future<Value::Outputs> outputs = promise->get_future().share();
    for (const auto& out : s.ports->outputs()) {
      const std::string key = s.id + "." + out.name;
      keep_call(key, values_[key] = {{}, outputs, out.name});
    }
    worker_.submit([this, &s, inputs = std::move(inputs), promise, iteration = s.iteration](std::exception_ptr earlier) {
      if (earlier) {
        promise->set_exception(earlier);
        return;
      }
      try {
        s.context->set_iteration(iteration);
        promise->set_value(process(s, inputs));
      } catch (...) {
        promise->set_exception(std::current_exception());
        throw;
      }
    });
  }

  void rethrow_background_error() {
    if (std::exception_ptr e = worker_.error()) std::rethrow_exception(e);
  }

  // Times a hook and puts the stage's name on anything it throws.
  template <class F>
  void timed(ResolvedStage& s, const char* hook, double& total, F&& f) {
    const auto t0 = Clock::now();
    const std::string who = "stage '" + s.id + "' (plugin " + s.plugin->name() + ")";
    const std::string when = s.context->iteration() >= 0
                                 ? " in iteration " + std::to_string(s.context->iteration()) : std::string();
    try {
      f();
    } catch (const ParameterError& e) {
      auto it = s.param_where.find(e.parameter());
      throw InputError(who + ", parameter '" + e.parameter() + "': " + e.detail(),
                       it != s.param_where.end() ? it->second : s.where);
    } catch (const InputError& e) {
      throw InputError(who + when + ": " + e.what(), s.where);
    } catch (const std::exception& e) {
      throw RunError(who + " failed in " + hook + when + ": " + e.what());
    } catch (...) {
      throw RunError(who + " failed in " + hook + when + " with an unknown exception");
    }
    total += seconds_since(t0);
  }

  ResolvedPipeline& pipeline_;
  const RunOptions& options_;
  const StreamOptions* stream_;  // null: not streaming
  std::vector<std::string> capture_;  // RunOptions::capture and, streaming, the outputs of its capture_types
  std::set<std::string> capture_keys_;  // the same, to look up
  Values values_;
  std::set<std::string> captured_;                          // RunOptions::capture
  std::map<std::string, std::vector<Value>> every_call_;  // RunOptions::capture_every_call
  std::map<const ResolvedLoop*, Values> previous_;
  // Last: destroyed first, so no background call outlives what it uses.
  BackgroundWorker worker_;
};

// Streaming reaches the runner through run_pipeline, Pipeline's friend.
thread_local const StreamOptions* streaming = nullptr;

}  // namespace

RunResult run_pipeline(Pipeline& pipeline, const RunOptions& options) {
  if (streaming) {
    bool top_level_loop = false;
    for (const auto& n : pipeline.impl_->nodes) top_level_loop |= n.loop != nullptr;
    if (!top_level_loop)
      throw InputError("stream runs a pipeline's top-level loop frame after frame, and " + pipeline.impl_->file.string() +
                       " has none (put its source and per-frame stages in a loop with until: SOURCE.done)");
  }
  return Runner(*pipeline.impl_, options, streaming).run();
}

RunResult stream_pipeline(Pipeline& pipeline, const RunOptions& options, const StreamOptions& stream) {
  streaming = &stream;
  struct Reset {
    ~Reset() { streaming = nullptr; }
  } reset;
  return run_pipeline(pipeline, options);
}

}  // namespace touchcloud
