#include "touchcloud/plugin_json.hpp"

namespace touchcloud {

namespace {

nlohmann::json param_json(const ParamSpec& p) {
  nlohmann::json j = {{"name", p.name}, {"type", to_string(p.type)}, {"unit", p.unit}, {"doc", p.doc},
                      {"rule", p.rule()}};
  if (p.default_value) std::visit([&j](const auto& v) { j["default"] = v; }, *p.default_value);
  else j["default"] = nullptr;  // "not set": the stage decides (its doc says how)
  if (p.optional) j["optional"] = true;
  if (!p.needs_feature.empty()) j["needs"] = {{"feature", p.needs_feature}, {"available", p.feature_available}};
  if (p.min) j["min"] = {{"value", *p.min}, {"exclusive", p.min_exclusive}};
  if (p.max) j["max"] = {{"value", *p.max}, {"exclusive", p.max_exclusive}};
  if (!p.choices.empty()) j["choices"] = p.choices;
  if (p.list_size) j["size"] = *p.list_size;
  if (p.path_role == PathRole::InputFile) j["file"] = "input";
  if (p.path_role == PathRole::OutputFile) j["file"] = "output";
  return j;
}

nlohmann::json port_json(const PortSpec& p) {
  nlohmann::json j = {{"name", p.name}, {"type", p.type}, {"doc", p.doc}, {"optional", p.optional}};
  if (!p.one_of.empty()) j["one_of"] = p.one_of;  // wire exactly one input of this group
  return j;
}

nlohmann::json metric_json(const MetricSpec& m) {
  nlohmann::json j = {{"name", m.name},
                      {"unit", m.unit},
                      {"doc", m.doc},
                      {"when", to_string(m.when)},
                      {"direction", to_string(m.direction)}};
  if (m.role != MetricRole::none) j["role"] = to_string(m.role);
  return j;
}

}  // namespace

nlohmann::json plugin_json(const LoadedPlugin& p) {
  nlohmann::json j = {{"name", p.name()},
                      {"category", to_string(p.category())},
                      {"description", p.description()},
                      {"library", p.library().string()},
                      {"built_for", p.toolkit_version()}};
  j["parameters"] = nlohmann::json::array();
  for (const auto& s : p.schema().parameters) j["parameters"].push_back(param_json(s));
  j["inputs"] = nlohmann::json::array();
  for (const auto& s : p.schema().inputs) j["inputs"].push_back(port_json(s));
  j["outputs"] = nlohmann::json::array();
  for (const auto& s : p.schema().outputs) j["outputs"].push_back(port_json(s));
  j["metrics"] = nlohmann::json::array();
  for (const auto& s : p.schema().metrics) j["metrics"].push_back(metric_json(s));
  j["artifacts"] = nlohmann::json::array();
  for (const auto& s : p.schema().artifacts) j["artifacts"].push_back({{"role", to_string(s.role)}, {"doc", s.doc}});
  return j;
}

}  // namespace touchcloud
