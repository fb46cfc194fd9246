// Collects every broken rule of an optics configuration and throws them
// together as one InputError, each naming the field, its value and the rule.
#pragma once

#include <string>
#include <vector>

#include "touchcloud/error.hpp"

namespace touchcloud::optics {

class ConfigCheck {
 public:
  explicit ConfigCheck(std::string what) : what_(std::move(what)) {}

  // Records "what.field = value: must be rule" unless ok.
  void require(bool ok, const std::string& field, const std::string& value, const std::string& rule);
  void require(bool ok, const std::string& field, double value, const std::string& rule);
  void throw_if_failed() const;

 private:
  std::string what_;
  std::vector<Diagnostic> problems_;
};

std::string format_number(double value);

}  // namespace touchcloud::optics
