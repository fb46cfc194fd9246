#include "config_check.hpp"

#include <sstream>

namespace touchcloud::optics {

std::string format_number(double value) {
  std::ostringstream s;
  s.precision(12);
  s << value;
  return s.str();
}

void ConfigCheck::require(bool ok, const std::string& field, const std::string& value,
                          const std::string& rule) {
  if (!ok) problems_.push_back({{}, what_ + "." + field + " = " + value + ": must be " + rule});
}

void ConfigCheck::require(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok) require(ok, field, format_number(value), rule);
}

void ConfigCheck::throw_if_failed() const {
  if (!problems_.empty()) throw InputError(problems_);
}

}  // namespace touchcloud::optics
