// The grid of settings a sweep runs: `--vary stage.param=V1,V2,...` axes,
// combined in full (every value of every axis with every other).
#pragma once

#include <string>
#include <vector>

#include "touchcloud/pipeline.hpp"

namespace touchcloud::cli {

struct SweepAxis {
  std::string key;                  // "stage.param"
  std::vector<std::string> values;  // YAML scalars or lists ("[1, 2]")
};

// Splits "k=v1,v2" at top-level commas (commas inside [...] stay). InputError
// naming the text when it is malformed.
SweepAxis parse_vary(const std::string& text);

// Every combination, first axis slowest; each a list of overrides.
std::vector<std::vector<Override>> sweep_settings(const std::vector<SweepAxis>& axes);

}  // namespace touchcloud::cli
