// The report page: one self-contained HTML file (libraries, script, style
// and data inline; nothing fetched when it is viewed).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace touchcloud::cli {

// The page for report_data()'s `data`; the same data gives the same bytes.
std::string report_html(const nlohmann::json& data);

}  // namespace touchcloud::cli
