// A plugin's description as JSON: what `touchcloud plugins --json` prints
// and the Python module's `touchcloud.plugins()` returns.
#pragma once

#include <nlohmann/json.hpp>

#include "touchcloud/plugin_registry.hpp"

namespace touchcloud {

// Name, category, description, library, parameters (type, default, unit,
// rule, range, choices), inputs, outputs, metrics and artifact roles.
nlohmann::json plugin_json(const LoadedPlugin& plugin);

}  // namespace touchcloud
