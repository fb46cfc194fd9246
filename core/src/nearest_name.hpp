// "Did you mean ...?" for unknown plugin, stage and parameter names.
#pragma once

#include <string>
#include <vector>

namespace touchcloud {

// The candidate closest to `name` by edit distance, or "" when none is close.
std::string nearest_name(const std::string& name, const std::vector<std::string>& candidates);
// "; did you mean 'x'?" or "".
std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace touchcloud
