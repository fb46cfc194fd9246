// A double as messages show it: the shortest text that reads back as the
// same number (std::to_chars), so 1e-300 is "1e-300", not "0.000000".
#pragma once

#include <string>

namespace touchcloud {

std::string number_text(double value);

}  // namespace touchcloud
