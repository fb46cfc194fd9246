// The sweep tests' pipeline: test_counter adds `step` per iteration for 3
// iterations (final value 3 * step); `params` are the counter's.
#pragma once

#include <string>

namespace touchcloud::test {

inline std::string counting_pipeline(const std::string& params = "step: 1") {
  return "stages:\n  - id: l\n    loop:\n      max_iterations: 3\n      stages:\n"
         "        - id: c\n          plugin: test_counter\n          params: {" + params + "}\n"
         "          inputs: {previous: c.value@previous}\n";
}

}  // namespace touchcloud::test
