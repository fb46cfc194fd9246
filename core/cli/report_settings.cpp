// Naming a folder's runs by their settings; see report_settings.hpp.
#include "report_settings.hpp"

#include <map>
#include <set>
#include <utility>

namespace touchcloud::cli {

namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;  // key, value as given

std::string trimmed(std::string text) {
  const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

// The run's overrides from `origin` ("" for every origin); none in a
// summary written before they were recorded.
Overrides overrides_of(const nlohmann::json& summary, const std::string& origin) {
  Overrides out;
  if (!summary.contains("overrides") || !summary["overrides"].is_array()) return out;
  for (const auto& o : summary["overrides"]) {
    if (!o.is_object() || !o.contains("key") || !o["key"].is_string() || !o.contains("value") || !o["value"].is_string())
      continue;
    if (!origin.empty() && o.value("origin", "") != origin) continue;
    out.emplace_back(o["key"].get<std::string>(), trimmed(o["value"].get<std::string>()));
  }
  return out;
}

std::string pipeline_of(const RunFolder& r) { return r.summary["pipeline"].value("name", std::string("run")); }

}  // namespace

RunNames name_runs(const std::vector<RunFolder>& runs) {
  std::vector<Overrides> varied(runs.size());
  bool any_vary = false;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    varied[i] = overrides_of(runs[i].summary, "--vary");
    any_vary = any_vary || !varied[i].empty();
  }
  if (!any_vary) {
    // Not a sweep's: the overrides whose values are not the same in every run.
    std::vector<std::map<std::string, std::string>> given(runs.size());
    std::map<std::string, std::set<std::string>> values;
    std::vector<std::string> order;
    for (std::size_t i = 0; i < runs.size(); ++i)
      for (const auto& [key, value] : overrides_of(runs[i].summary, "")) {
        if (!values.count(key)) order.push_back(key);
        given[i][key] = value;  // the last of a repeated key is the one applied
        values[key].insert(value);
      }
    for (std::size_t i = 0; i < runs.size(); ++i)
      for (const auto& key : order) {
        const bool everywhere = values[key].size() == 1 && [&] {
          for (const auto& g : given)
            if (!g.count(key)) return false;
          return true;
        }();
        if (everywhere) continue;
        varied[i].emplace_back(key, given[i].count(key) ? given[i][key] : "(not set)");
      }
  }
  std::set<std::string> pipelines;
  for (const auto& r : runs) pipelines.insert(pipeline_of(r));

  RunNames names;
  std::map<std::string, int> uses;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    std::string name = pipelines.size() > 1 || varied[i].empty() ? pipeline_of(runs[i]) : "";
    for (const auto& [key, value] : varied[i]) name += (name.empty() ? "" : ", ") + key + "=" + value;
    names.setting.push_back(name);
    const auto& seed = runs[i].summary.contains("seed") ? runs[i].summary["seed"] : nlohmann::json();
    names.run.push_back(name + ", seed " + (seed.is_number() ? seed.dump() : std::string("?")));
    ++uses[names.run.back()];
  }
  // Copies of one run (same setting and seed) are told apart by their folders.
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (uses[names.run[i]] > 1) names.run[i] += " (" + runs[i].label + ")";
  return names;
}

}  // namespace touchcloud::cli
