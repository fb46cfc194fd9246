#include "touchcloud/number_text.hpp"

#include <charconv>

namespace touchcloud {

std::string number_text(double value) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, r.ptr);
}

}  // namespace touchcloud
