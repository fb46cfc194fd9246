#include "touchcloud/error.hpp"

namespace touchcloud {

std::string SourceLocation::str() const {
  if (file.empty()) return {};
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column > 0 ? column : 1);
}

std::string Diagnostic::str() const {
  const std::string at = where.str();
  return (at.empty() ? std::string() : at + ": ") + "error: " + message;
}

namespace {
// what(): "where: message" lines, without the "error:" of the CLI format, so
// a message can be wrapped and rethrown.
std::string join_diagnostics(const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const auto& d : diagnostics) {
    const std::string at = d.where.str();
    text += (text.empty() ? "" : "\n") + (at.empty() ? "" : at + ": ") + d.message;
  }
  return text;
}
}  // namespace

InputError::InputError(std::string message, SourceLocation where)
    : InputError(std::vector<Diagnostic>{{std::move(where), std::move(message)}}) {}

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join_diagnostics(diagnostics)), diagnostics_(std::move(diagnostics)) {}

ParameterError::ParameterError(std::string parameter, std::string message)
    : InputError("parameter '" + parameter + "': " + message),
      parameter_(std::move(parameter)),
      detail_(std::move(message)) {}

InputError::~InputError() = default;
ParameterError::~ParameterError() = default;
RunError::~RunError() = default;

}  // namespace touchcloud
