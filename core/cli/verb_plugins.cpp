// touchcloud plugins [NAME] [--json]: what plugins there are and what they take.
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "touchcloud/plugin_json.hpp"
#include "touchcloud/plugin_registry.hpp"
#include "verbs.hpp"

namespace touchcloud::cli {

namespace {

void print_parameter(const ParamSpec& p) {
  std::string type = to_string(p.type);
  if (p.path_role == PathRole::InputFile) type = "input file";
  if (p.path_role == PathRole::OutputFile) type = "output file";
  std::cout << "    " << std::left << std::setw(22) << p.name << " " << std::setw(15) << type
            << (p.default_value ? " default " + format_value(*p.default_value) : std::string(" not set"))
            << (p.unit.empty() ? "" : " " + p.unit);
  if (!p.rule().empty()) std::cout << "; " << p.rule();
  if (!p.needs_feature.empty())
    std::cout << "; needs " << p.needs_feature << (p.feature_available ? "" : " (not in this build)");
  std::cout << "\n" << std::string(28, ' ') << p.doc << "\n";
}

void print_plugin(const LoadedPlugin& p, bool full) {
  std::cout << p.name() << " - " << p.description() << "\n";
  if (full) std::cout << "  category: " << category_title(p.category()) << "\n";
  if (full) std::cout << "  library: " << p.library().string() << " (built for touchcloud " << p.toolkit_version() << ")\n";
  const auto& s = p.schema();
  if (!s.parameters.empty()) {
    std::cout << "  parameters:\n";
    for (const auto& param : s.parameters) print_parameter(param);
  }
  if (!full) return;
  const auto ports = [](const char* title, const std::vector<PortSpec>& list) {
    if (list.empty()) return;
    std::cout << "  " << title << ":\n";
    for (const auto& port : list)
      std::cout << "    " << std::left << std::setw(22) << port.name << " " << std::setw(15) << port.type
                << (!port.one_of.empty() ? " (one of its " + port.one_of + ") "
                    : port.optional      ? std::string(" (optional) ")
                                         : std::string(" "))
                << port.doc << "\n";
  };
  ports("inputs", s.inputs);
  ports("outputs", s.outputs);
  if (!s.metrics.empty()) {
    std::cout << "  metrics:\n";
    for (const auto& m : s.metrics) {
      std::string traits = to_string(m.when);
      if (m.direction != MetricDirection::none) traits += std::string(", ") + to_string(m.direction);
      if (m.role != MetricRole::none) traits += std::string(", role ") + to_string(m.role);
      std::cout << "    " << std::left << std::setw(22) << m.name << " " << std::setw(15)
                << (m.unit.empty() ? "-" : m.unit) << " " << m.doc << " (" << traits << ")\n";
    }
  }
  if (!s.artifacts.empty()) {
    std::cout << "  writes:\n";
    for (const auto& a : s.artifacts) std::cout << "    " << std::left << std::setw(22) << to_string(a.role) << " " << a.doc << "\n";
  }
}

}  // namespace

Action* add_plugins_verb(CLI::App& app) {
  struct Options {
    std::string name;
    bool json = false;
  };
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand("plugins", "List the plugins on the search path, or describe one");
  cmd->add_option("name", o.name, "plugin to describe in full");
  cmd->add_flag("--json", o.json, "machine-readable output");
  cmd->callback([] {
    action = [] {
      PluginRegistry registry;
      if (!o.name.empty()) {
        const LoadedPlugin& p = registry.load(o.name);
        if (o.json) std::cout << plugin_json(p).dump(2) << "\n";
        else print_plugin(p, true);
        return kExitOk;
      }
      nlohmann::json all = nlohmann::json::array();
      int failed = 0;
      std::vector<const LoadedPlugin*> loaded;
      for (const auto& name : registry.available()) {
        try {
          loaded.push_back(&registry.load(name));
        } catch (const InputError& e) {
          ++failed;
          std::cerr << "touchcloud: error: " << e.what() << "\n";
        }
      }
      // --json: by name, each with its category; the text: grouped by
      // category, in the order of PluginCategory, by name within.
      if (o.json)
        for (const LoadedPlugin* p : loaded) all.push_back(plugin_json(*p));
      for (const PluginCategory category : kPluginCategories) {
        bool headed = false;
        for (const LoadedPlugin* p : loaded) {
          if (o.json || p->category() != category) continue;
          if (!headed) std::cout << "== " << category_title(category) << " ==\n\n";
          headed = true;
          print_plugin(*p, false);
          std::cout << "\n";
        }
      }
      if (o.json) std::cout << all.dump(2) << "\n";
      else {
        std::cout << "search path:";
        for (const auto& f : registry.search_path()) std::cout << " " << f.string();
        std::cout << "\n";
      }
      return failed ? kExitBadInput : kExitOk;
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
