// PipelineDoc -> ResolvedPipeline: overrides, plugins, parameters, wiring,
// execution order, and each stage's own checks. Collects every problem it
// can find before giving up, each with its file position.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "nearest_name.hpp"
#include "output_name.hpp"
#include "touchcloud/path_text.hpp"
#include "touchcloud/run_context.hpp"
#include "pipeline_model.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

const std::string& ResolvedNode::id() const { return stage ? stage->id : loop->id; }

namespace {

// Where every node sits: its enclosing loops (outermost first).
struct NodeInfo {
  NodeDoc* doc = nullptr;
  std::vector<NodeDoc*> loops;
};

class Resolver {
 public:
  Resolver(PipelineDoc doc, PluginRegistry& registry) : doc_(std::move(doc)), registry_(registry) {}

  std::unique_ptr<ResolvedPipeline> run(const std::vector<Override>& overrides) {
    index(doc_.nodes, {});
    for (const auto& o : overrides) apply_override(o);
    auto pipeline = std::make_unique<ResolvedPipeline>();
    pipeline->name = doc_.name;
    pipeline->file = doc_.file;
    pipeline->overrides = overrides;
    pipeline_ = pipeline.get();
    name_scene(*pipeline);
    pipeline->nodes = resolve_scope(doc_.nodes, {});
    if (diags_.empty()) check_one_scene();
    if (diags_.empty()) check_wiring(doc_.nodes);
    if (diags_.empty()) run_checks();
    if (!diags_.empty()) throw InputError(diags_);
    return pipeline;
  }

 private:
  void error(SourceLocation where, std::string message) { diags_.push_back({std::move(where), std::move(message)}); }

  void index(std::vector<NodeDoc>& nodes, std::vector<NodeDoc*> loops) {
    for (auto& n : nodes) {
      if (n.id.empty()) continue;
      if (auto it = nodes_.find(n.id); it != nodes_.end())
        error(n.where, "duplicate stage id '" + n.id + "' (first defined at " + it->second.doc->where.str() + ")");
      else
        nodes_[n.id] = {&n, loops};
      if (n.is_loop) {
        auto inner = loops;
        inner.push_back(&n);
        index(n.body, inner);
      }
    }
  }

  std::vector<std::string> ids() const {
    std::vector<std::string> out;
    for (const auto& [id, info] : nodes_) out.push_back(id);
    return out;
  }

  void apply_override(const Override& o) {
    if (o.key == kPipelineSceneKey) {  // --scene FILE: the run's one scene
      doc_.scene = ParamDoc{"scene", YAML::Node(o.value), SourceLocation{o.origin + " " + o.value}, true};
      return;
    }
    const SourceLocation where{o.origin + " " + o.key + "=" + o.value};
    const auto dot = o.key.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == o.key.size()) {
      error(where, "'" + o.key + "' must be STAGE.PARAM");
      return;
    }
    const std::string id = o.key.substr(0, dot), name = o.key.substr(dot + 1);
    auto it = nodes_.find(id);
    if (it == nodes_.end()) {
      error(where, "no stage with id '" + id + "'" + did_you_mean(id, ids()));
      return;
    }
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception& e) {
      error(where, "value '" + o.value + "' is not valid YAML: " + e.msg);
      return;
    }
    NodeDoc& node = *it->second.doc;
    if (node.is_loop) {
      std::int64_t n = 0;
      if (name != "max_iterations") error(where, "loop '" + id + "' has only 'max_iterations' to set");
      else if (!value.IsScalar() || !(std::istringstream(value.Scalar()) >> n) || n < 1 ||
               std::to_string(n) != value.Scalar())
        error(where, "'max_iterations' must be an integer >= 1, got '" + o.value + "'");
      else
        node.max_iterations = n;
      return;
    }
    for (auto& p : node.params)
      if (p.name == name) {
        // reset() rebinds this stage's value; assigning a YAML::Node would
        // overwrite the node itself, which a YAML anchor shares with others.
        p.value.reset(value);
        p.where = where;
        p.from_command_line = true;
        return;
      }
    node.params.push_back({name, value, where, true});
  }

  std::vector<ResolvedNode> resolve_scope(std::vector<NodeDoc>& nodes, std::vector<const ResolvedLoop*> loops) {
    std::vector<ResolvedNode> out;
    for (auto& n : nodes) {
      ResolvedNode r;
      if (n.is_loop) {
        r.loop = std::make_unique<ResolvedLoop>();
        r.loop->id = n.id;
        r.loop->where = n.where;
        r.loop->max_iterations = n.max_iterations;
        auto inner = loops;
        inner.push_back(r.loop.get());
        r.loop->body = resolve_scope(n.body, inner);
        loops_[n.id] = r.loop.get();
        pipeline_->loops.push_back(r.loop.get());
      } else {
        r.stage = resolve_stage(n);
        if (!r.stage) continue;
        r.stage->loops = loops;
        stages_[n.id] = r.stage.get();
        in_file_order_.push_back(r.stage.get());
      }
      out.push_back(std::move(r));
    }
    return out;
  }

  std::unique_ptr<ResolvedStage> resolve_stage(NodeDoc& n) {
    if (n.plugin.empty()) return nullptr;
    const LoadedPlugin* plugin = nullptr;
    try {
      plugin = &registry_.load(n.plugin);
    } catch (const InputError& e) {
      error(n.plugin_where, "stage '" + n.id + "': " + e.what());
      return nullptr;
    }
    auto s = std::make_unique<ResolvedStage>();
    s->id = n.id;
    s->where = n.where;
    s->background = n.background;
    s->plugin = plugin;
    s->stage = plugin->create();
    s->params = std::make_unique<ParameterSet>();
    s->ports = std::make_unique<PortSet>();
    s->stage->declare(*s->params, *s->ports);
    for (const auto& spec : s->params->specs())
      if (spec.default_value) s->values[spec.name] = *spec.default_value;

    const std::string who = "stage '" + n.id + "' (plugin " + n.plugin + ")";
    if (n.own_scene) {
      if (!s->params->find("scene")) error(n.own_scene_where, who + " takes no scene: 'own_scene' is for a stage "
                                                                 "with a 'scene' parameter");
      own_scene_.insert(n.id);
    } else if (s->params->find("scene")) {
      take_pipeline_scene(n);
    }
    std::vector<std::string> names;
    for (const auto& spec : s->params->specs()) names.push_back(spec.name);
    for (const auto& p : n.params) {
      const ParamSpec* spec = s->params->find(p.name);
      if (!spec) {
        error(p.where, who + " has no parameter '" + p.name + "'" + did_you_mean(p.name, names) +
                           " (see `touchcloud plugins " + n.plugin + "`)");
        continue;
      }
      if (spec->optional && (!p.value || p.value.IsNull())) {  // `name: ~` leaves it "not set"
        s->params->unset(p.name);
        s->values.erase(p.name);
        s->param_where[p.name] = p.where;
        continue;
      }
      std::string why;
      auto value = convert_param(*spec, p.value, why);
      if (!value) {
        error(p.where, who + ", parameter '" + p.name + "': " + why);
        continue;
      }
      if (spec->path_role == PathRole::InputFile && !resolve_input_file(*spec, *value, p, who)) continue;
      if (spec->path_role == PathRole::OutputFile) {
        // "{pipeline}" names outputs after the pipeline, so a copy of a
        // shipped pipeline renamed for another object names its files anew.
        *value = with_pipeline_name(std::get<std::string>(*value), doc_.name);
        if (std::get<std::string>(*value).find(kSceneField) != std::string::npos) {
          if (pipeline_->scene_name.empty()) {
            error(p.where, who + ", parameter '" + p.name + "': '" + kSceneField +
                               "' needs the run's scene: a top-level 'scene: FILE' or --scene FILE");
            continue;
          }
          *value = with_scene_name(std::get<std::string>(*value), pipeline_->scene_name);
        }
        // `validate` refuses what `run` would: a file outside the output folder.
        if (auto why = output_name_problem(std::get<std::string>(*value))) {
          error(p.where, who + ", parameter '" + p.name + "': " + *why);
          continue;
        }
      }
      try {
        s->params->assign(p.name, *value);
        s->values[p.name] = *value;
        s->param_where[p.name] = p.where;
      } catch (const ParameterError& e) {
        error(p.where, who + ", parameter '" + p.name + "': " + e.detail());
      }
    }
    // An input file has no usable default: the pipeline must name one.
    for (const auto& spec : s->params->specs())
      if (spec.path_role == PathRole::InputFile && !spec.optional &&
          std::none_of(n.params.begin(), n.params.end(), [&](const ParamDoc& p) { return p.name == spec.name; }))
        error(n.where, who + ": parameter '" + spec.name + "' names an input file and must be set");
    return s;
  }

  // The run's scene by file and name, for summary.json, the report's title
  // and "{scene}" in output names. A file that cannot be read is left to the
  // stages that take it, which say so with its place.
  void name_scene(ResolvedPipeline& pipeline) const {
    if (!doc_.scene) return;
    fs::path file = doc_.scene->value.as<std::string>("");
    if (file.empty()) return;
    if (file.is_relative() && !doc_.scene->from_command_line) file = doc_.file.parent_path() / file;
    pipeline.scene_file = fs::absolute(file).lexically_normal();
    pipeline.scene_name = pipeline.scene_file.stem().string();
    try {
      const YAML::Node scene = YAML::LoadFile(pipeline.scene_file.string());
      if (scene.IsMap() && scene["name"] && scene["name"].IsScalar()) pipeline.scene_name = scene["name"].as<std::string>();
    } catch (const YAML::Exception&) {
    }
  }

  // The pipeline's scene goes to a stage that names none; --scene replaces
  // the one it names, unless --set named the stage's own.
  void take_pipeline_scene(NodeDoc& n) {
    if (!doc_.scene) return;
    auto own = std::find_if(n.params.begin(), n.params.end(), [](const ParamDoc& p) { return p.name == "scene"; });
    if (own == n.params.end()) {
      n.params.push_back(*doc_.scene);
    } else if (doc_.scene->from_command_line && !own->from_command_line) {
      own->value.reset(doc_.scene->value);  // reset(): the node may be an anchor other stages share
      own->where = doc_.scene->where;
      own->from_command_line = true;
    }
  }

  // Every stage that takes a scene names the one the simulator simulates
  // (its first simulator stage, in file order), unless it says `own_scene`:
  // a chamfer against one object while the sensor touches another scores
  // nothing the run did.
  void check_one_scene() {
    const auto scene_of = [](const ResolvedStage& s) -> const std::string* {
      auto it = s.values.find("scene");
      if (it == s.values.end()) return nullptr;
      const auto* file = std::get_if<std::string>(&it->second);
      return file && !file->empty() ? file : nullptr;
    };
    const ResolvedStage* simulator = nullptr;
    for (const auto* s : in_file_order_)
      if (s->plugin->category() == PluginCategory::simulation && scene_of(*s) && !own_scene_.count(s->id)) {
        simulator = s;
        break;
      }
    if (!simulator) return;
    std::error_code ec;
    const std::string& simulated = *scene_of(*simulator);
    for (const auto* s : in_file_order_) {
      const std::string* scene = scene_of(*s);
      if (s == simulator || !scene || own_scene_.count(s->id)) continue;
      if (*scene == simulated || fs::equivalent(*scene, simulated, ec)) continue;
      auto where = s->param_where.find("scene");
      error(where != s->param_where.end() ? where->second : s->where,
            "stage '" + s->id + "' (plugin " + s->plugin->name() + ") names the scene " + absolute_text(*scene) +
                " but stage '" + simulator->id + "' simulates " + absolute_text(simulated) +
                ": name the scene once (top-level 'scene: FILE', or --scene FILE), or add 'own_scene: true' to "
                "the stage if it means another scene");
    }
  }

  // Relative input files are relative to the pipeline file's folder (to the
  // working directory for --set); they must exist and be readable, except a
  // per-iteration pattern ("frame_{iteration}.png"), whose folder must exist.
  // Where a relative path was taken from, for "does not exist" messages.
  std::string relative_to(const fs::path& given, const ParamDoc& p) const {
    if (!given.is_relative()) return "";
    return p.from_command_line ? " (--set paths are relative to the current directory)"
                               : " (paths in a pipeline are relative to its file's folder, " +
                                     absolute_text(doc_.file.parent_path()) + ")";
  }

  bool resolve_input_file(const ParamSpec& spec, ParamValue& value, const ParamDoc& p, const std::string& who) {
    const fs::path given = std::get<std::string>(value);
    fs::path path = given;
    if (path.is_relative() && !p.from_command_line) path = doc_.file.parent_path() / path;
    path = path.lexically_normal();
    std::error_code ec;
    if (path.string().find(kIterationField) != std::string::npos) {
      // One file per loop iteration: the stage reads them as the loop runs;
      // here only the folder can be checked.
      if (!fs::is_directory(path.parent_path(), ec)) {
        error(p.where, who + ", parameter '" + spec.name + "': folder " + absolute_text(path.parent_path()) +
                           " does not exist" + relative_to(given, p));
        return false;
      }
      value = path.string();
      return true;
    }
    if (!fs::exists(path, ec)) {
      error(p.where, who + ", parameter '" + spec.name + "': input file " + absolute_text(path) + " does not exist" +
                         relative_to(given, p));
      return false;
    }
    if (fs::is_directory(path, ec)) {
      error(p.where, who + ", parameter '" + spec.name + "': " + path.string() + " is a folder, not a file");
      return false;
    }
    // Opening a FIFO blocks until someone writes to it.
    if (!fs::is_regular_file(path, ec)) {
      error(p.where, who + ", parameter '" + spec.name + "': " + path.string() +
                         " is not a regular file (a FIFO, socket or device)");
      return false;
    }
    if (!std::ifstream(path)) {
      error(p.where, who + ", parameter '" + spec.name + "': cannot read input file " + path.string());
      return false;
    }
    value = path.string();
    return true;
  }

  // Inputs, `until`, and the order of execution in every scope.
  void check_wiring(std::vector<NodeDoc>& nodes) {
    for (auto& n : nodes) {
      if (n.is_loop) {
        check_wiring(n.body);
        check_until(n);
        continue;
      }
      auto* s = stages_.at(n.id);
      const std::string who = "stage '" + n.id + "' (plugin " + n.plugin + ")";
      std::set<std::string> wired;
      std::vector<std::string> input_names;
      for (const auto& in : s->ports->inputs()) input_names.push_back(in.name);
      for (const auto& ref : n.inputs) {
        const PortSpec* in = s->ports->find_input(ref.port);
        if (!in) {
          error(ref.where, who + " has no input '" + ref.port + "'" + did_you_mean(ref.port, input_names));
          continue;
        }
        if (!wired.insert(ref.port).second) error(ref.where, who + ": input '" + ref.port + "' is wired twice");
        if (ref.stage == n.id && !ref.previous) {
          error(ref.where, "the inputs form a cycle: " + n.id + " -> " + n.id + " (stage '" + n.id +
                               "' reads its own output " + ref.stage + "." + ref.output +
                               "; inside a loop, read the previous iteration's with '@previous')");
          continue;
        }
        const PortSpec* out = find_output(ref, who + ", input '" + ref.port + "'");
        if (!out) continue;
        if (out->type != in->type) {
          error(ref.where, who + ", input '" + ref.port + "' takes " + in->type + " but " + ref.stage + "." +
                               ref.output + " gives " + out->type);
          continue;
        }
        stages_.at(ref.stage)->wanted_outputs.insert(ref.output);
        if (ref.previous || inside_innermost_loop_of(n.id, ref.stage)) stages_.at(ref.stage)->read_in_loop.insert(ref.output);
        ResolvedInput r{ref.port, ref.stage + "." + ref.output, nullptr};
        if (ref.previous) {
          r.previous_of = common_loop(n.id, ref.stage);
          if (!r.previous_of) {
            error(ref.where, who + ", input '" + ref.port + "': '@previous' needs " + ref.stage +
                                 " and this stage inside one loop");
            continue;
          }
          if (!in->optional)
            error(ref.where, who + ", input '" + ref.port + "' is fed from the previous iteration, which the first "
                                 "iteration does not have, but the plugin requires it");
        }
        s->inputs.push_back(r);
      }
      for (const auto& in : s->ports->inputs())
        if (!in.optional && !wired.count(in.name))
          error(n.where, who + " is missing its input '" + in.name + "' (" + in.type + "): add inputs: {" +
                             in.name + ": STAGE.OUTPUT}");
      check_one_of(n, who, *s->ports, wired);
    }
    if (diags_.empty()) order_scope(nodes);
  }

  // Each group of one_of inputs has exactly one of them wired.
  void check_one_of(const NodeDoc& n, const std::string& who, const PortSet& ports, const std::set<std::string>& wired) {
    std::map<std::string, std::vector<const PortSpec*>> groups;
    for (const auto& in : ports.inputs())
      if (!in.one_of.empty()) groups[in.one_of].push_back(&in);
    for (const auto& [group, inputs] : groups) {
      std::string names, wired_names;
      int wired_count = 0;
      for (const PortSpec* in : inputs) {
        names += (names.empty() ? "'" : "' or '") + in->name;
        if (!wired.count(in->name)) continue;
        wired_names += (wired_count++ == 0 ? "'" : "' and '") + in->name;
      }
      names += "'";
      if (wired_count == 0)
        error(n.where, who + " is missing its " + group + ": wire one of its inputs " + names + " (add inputs: {" +
                           inputs.front()->name + ": STAGE.OUTPUT})");
      else if (wired_count > 1)
        error(n.where, who + " takes one of its inputs " + names + " (its " + group + "), but " + wired_names +
                           "' are wired");
    }
  }

  const PortSpec* find_output(const InputRefDoc& ref, const std::string& who) {
    auto it = stages_.find(ref.stage);
    if (it == stages_.end()) {
      error(ref.where, who + " reads from unknown stage '" + ref.stage + "'" + did_you_mean(ref.stage, ids()) +
                           (loops_.count(ref.stage) ? " (a loop has no outputs; read a stage inside it)" : ""));
      return nullptr;
    }
    const PortSpec* out = it->second->ports->find_output(ref.output);
    if (!out) {
      std::vector<std::string> names;
      for (const auto& o : it->second->ports->outputs()) names.push_back(o.name);
      error(ref.where, who + ": stage '" + ref.stage + "' (plugin " + it->second->plugin->name() +
                           ") has no output '" + ref.output + "'" + did_you_mean(ref.output, names));
    }
    return out;
  }

  void check_until(NodeDoc& n) {
    if (!n.until) return;
    const std::string who = "loop '" + n.id + "', 'until'";
    const PortSpec* out = find_output(*n.until, who);
    if (!out) return;
    if (out->type != "bool") {
      error(n.until->where, who + ": " + n.until->stage + "." + n.until->output + " gives " + out->type +
                                ", not bool");
      return;
    }
    const auto& loops = nodes_.at(n.until->stage).loops;
    if (std::find(loops.begin(), loops.end(), &n) == loops.end()) {
      error(n.until->where, who + ": stage '" + n.until->stage + "' is not inside this loop");
      return;
    }
    loops_.at(n.id)->until_key = n.until->stage + "." + n.until->output;
    stages_.at(n.until->stage)->wanted_outputs.insert(n.until->output);
    stages_.at(n.until->stage)->read_in_loop.insert(n.until->output);
  }

  // Whether `reader` runs inside the innermost loop around `producer` (false
  // when the producer is in no loop: then nothing is read "after" it).
  bool inside_innermost_loop_of(const std::string& reader, const std::string& producer) const {
    const auto& around = nodes_.at(producer).loops;
    if (around.empty()) return true;
    const auto& reader_loops = nodes_.at(reader).loops;
    return std::find(reader_loops.begin(), reader_loops.end(), around.back()) != reader_loops.end();
  }

  const ResolvedLoop* common_loop(const std::string& a, const std::string& b) {
    const auto& la = nodes_.at(a).loops;
    const auto& lb = nodes_.at(b).loops;
    const NodeDoc* common = nullptr;
    for (std::size_t i = 0; i < std::min(la.size(), lb.size()) && la[i] == lb[i]; ++i) common = la[i];
    return common ? loops_.at(common->id) : nullptr;
  }

  // The child of `scope` that holds node `id` (itself, or the loop around it).
  const NodeDoc* ancestor_in(const std::vector<NodeDoc>& scope, const std::string& id) {
    const NodeInfo& info = nodes_.at(id);
    for (const auto& n : scope) {
      if (&n == info.doc) return &n;
      for (const NodeDoc* loop : info.loops)
        if (loop == &n) return &n;
    }
    return nullptr;
  }

  // Every stage inside `n` (or `n` itself) with the references it makes.
  void collect_refs(const NodeDoc& n, std::vector<const InputRefDoc*>& refs) {
    if (!n.is_loop) {
      for (const auto& r : n.inputs)
        if (!r.previous) refs.push_back(&r);
      return;
    }
    for (const auto& b : n.body) collect_refs(b, refs);
  }

  // Topological order of one scope, file order among equals; a cycle is an error.
  void order_scope(std::vector<NodeDoc>& scope) {
    const std::size_t count = scope.size();
    std::vector<std::set<std::size_t>> deps(count);
    for (std::size_t i = 0; i < count; ++i) {
      std::vector<const InputRefDoc*> refs;
      collect_refs(scope[i], refs);
      for (const auto* r : refs) {
        const NodeDoc* from = ancestor_in(scope, r->stage);
        if (!from || from == &scope[i]) continue;  // outside this scope, or inside the same loop
        deps[i].insert(static_cast<std::size_t>(from - scope.data()));
      }
    }
    std::vector<int> state(count, 0);  // 0 new, 1 on the stack, 2 done
    std::vector<std::size_t> order, stack;
    std::function<bool(std::size_t)> visit = [&](std::size_t i) {
      if (state[i] == 2) return true;
      if (state[i] == 1) {
        std::string cycle;
        auto start = std::find(stack.begin(), stack.end(), i);
        for (auto it = start; it != stack.end(); ++it) cycle += scope[*it].id + " -> ";
        error(scope[i].where, "the inputs form a cycle: " + cycle + scope[i].id +
                                  " (feed an earlier iteration with 'stage.output@previous' inside a loop)");
        return false;
      }
      state[i] = 1;
      stack.push_back(i);
      for (std::size_t d : deps[i])
        if (!visit(d)) return false;
      stack.pop_back();
      state[i] = 2;
      order.push_back(i);
      return true;
    };
    for (std::size_t i = 0; i < count; ++i)
      if (!visit(i)) return;
    order_[&scope] = order;
  }

  void run_checks() {
    reorder(pipeline_->nodes, doc_.nodes);
    for (auto* s : pipeline_->stages) {
      s->context = std::make_unique<RunContext>(s->id, 0, pipeline_->record);
      try {
        const auto started = std::chrono::steady_clock::now();
        s->stage->check(*s->context);
        s->timing.check_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      } catch (const ParameterError& e) {
        auto it = s->param_where.find(e.parameter());
        error(it != s->param_where.end() ? it->second : s->where,
              "stage '" + s->id + "' (plugin " + s->plugin->name() + "), parameter '" + e.parameter() + "': " +
                  e.detail());
      } catch (const InputError& e) {
        error(s->where, "stage '" + s->id + "' (plugin " + s->plugin->name() + "): " + e.what());
      } catch (const std::exception& e) {
        error(s->where, "stage '" + s->id + "' (plugin " + s->plugin->name() + ") failed its checks: " + e.what());
      }
    }
  }

  // Puts resolved nodes in execution order and lists stages in that order.
  void reorder(std::vector<ResolvedNode>& nodes, std::vector<NodeDoc>& docs) {
    std::vector<ResolvedNode> ordered;
    for (std::size_t i : order_.at(&docs)) {
      ResolvedNode& n = nodes[i];
      if (n.loop) {
        const std::size_t first = pipeline_->stages.size();
        reorder(n.loop->body, docs[i].body);
        for (std::size_t k = first; k < pipeline_->stages.size(); ++k) n.loop->stages.push_back(pipeline_->stages[k]);
      } else {
        pipeline_->stages.push_back(n.stage.get());
      }
      ordered.push_back(std::move(n));
    }
    nodes = std::move(ordered);
  }

  PipelineDoc doc_;
  PluginRegistry& registry_;
  std::vector<Diagnostic> diags_;
  ResolvedPipeline* pipeline_ = nullptr;
  std::map<std::string, NodeInfo> nodes_;
  std::map<std::string, ResolvedStage*> stages_;
  std::vector<ResolvedStage*> in_file_order_;
  std::set<std::string> own_scene_;  // stages with `own_scene: true`
  std::map<std::string, ResolvedLoop*> loops_;
  std::map<const std::vector<NodeDoc>*, std::vector<std::size_t>> order_;
};

}  // namespace

std::unique_ptr<ResolvedPipeline> resolve_pipeline(PipelineDoc doc, const std::vector<Override>& overrides,
                                                   PluginRegistry& registry) {
  return Resolver(std::move(doc), registry).run(overrides);
}

}  // namespace touchcloud
