#include "run_summary.hpp"

#include "touchcloud/library_versions.hpp"

namespace touchcloud {

namespace {
nlohmann::json to_json(const ParamValue& v) {
  return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}
}  // namespace

nlohmann::json make_summary(const ResolvedPipeline& pipeline, const RunResult& result, const RunOptions& options) {
  nlohmann::json j;
  j["pipeline"] = {{"name", pipeline.name}, {"file", pipeline.file.string()}};
  if (!pipeline.scene_file.empty()) j["scene"] = {{"name", pipeline.scene_name}, {"file", pipeline.scene_file.string()}};
  j["seed"] = options.seed;
  nlohmann::json overrides = nlohmann::json::array();
  for (const auto& o : pipeline.overrides) overrides.push_back({{"key", o.key}, {"value", o.value}, {"origin", o.origin}});
  j["overrides"] = overrides;
  j["versions"] = library_versions();
  j["versions"]["plugin_abi"] = kPluginAbiVersion;
  j["wall_time_s"] = result.wall_time_s;
  j["load_time_s"] = result.load_time_s;

  nlohmann::json stages = nlohmann::json::array();
  for (const auto* s : pipeline.stages) {
    // Each parameter as used: the value a stage chose for one left "not
    // set" (RunContext::used), else the value set or the default.
    const auto used = result.record.used.find(s->id);
    const auto chosen = [&](const std::string& name) -> const ParamValue* {
      if (used == result.record.used.end()) return nullptr;
      auto it = used->second.find(name);
      return it == used->second.end() ? nullptr : &it->second;
    };
    nlohmann::json params = nlohmann::json::object();
    for (const auto& spec : s->params->specs()) {
      const auto value = s->values.find(spec.name);
      if (const ParamValue* v = chosen(spec.name); v && value == s->values.end()) params[spec.name] = to_json(*v);
      else if (value != s->values.end()) params[spec.name] = to_json(value->second);
      else params[spec.name] = nullptr;
    }
    nlohmann::json stage = {{"id", s->id},
                            {"plugin", s->plugin->name()},
                            {"plugin_built_for", s->plugin->toolkit_version()},
                            {"library", s->plugin->library().string()},
                            {"params", params}};
    if (s->background) stage["background"] = true;
    // What else the stage reports it used (a build's backend, its threads).
    if (used != result.record.used.end()) {
      nlohmann::json other = nlohmann::json::object();
      for (const auto& [name, value] : used->second)
        if (!s->params->find(name)) other[name] = to_json(value);
      if (!other.empty()) stage["used"] = other;
    }
    for (const auto& t : result.timings)
      if (t.id == s->id)
        stage["time_s"] = {{"check", t.check_s}, {"configure", t.configure_s}, {"process", t.process_s},
                           {"finish", t.finish_s}, {"calls", t.calls}};
    stages.push_back(stage);
  }
  j["stages"] = stages;

  nlohmann::json loops = nlohmann::json::object();
  for (const auto& [id, n] : result.loop_iterations) loops[id] = {{"iterations", n}};
  for (const auto* l : pipeline.loops) loops[l->id]["max_iterations"] = l->max_iterations;
  j["loops"] = loops;

  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& [name, series] : result.record.metrics) {
    const MetricSpec& spec = series.spec;
    nlohmann::json m = {{"value", series.values.back()}, {"unit", spec.unit}};
    if (series.values.size() > 1) m["series"] = series.values;
    if (!spec.doc.empty()) m["doc"] = spec.doc;
    m["when"] = to_string(spec.when);
    if (spec.direction != MetricDirection::none) m["direction"] = to_string(spec.direction);
    if (spec.role != MetricRole::none) m["role"] = to_string(spec.role);
    metrics[name] = m;
  }
  j["metrics"] = metrics;
  j["notes"] = result.record.notes;
  j["outputs"] = result.record.outputs;
  nlohmann::json artifacts = nlohmann::json::array();
  for (const auto& a : result.record.artifacts) {
    nlohmann::json attributes = nlohmann::json::object();
    for (const auto& [key, value] : a.attributes) attributes[key] = to_json(value);
    nlohmann::json entry = {{"stage", a.stage}, {"role", to_string(a.role)}, {"attributes", attributes}};
    entry["file"] = a.file.empty() ? nlohmann::json() : nlohmann::json(a.file);
    artifacts.push_back(entry);
  }
  j["artifacts"] = artifacts;
  return j;
}

}  // namespace touchcloud
