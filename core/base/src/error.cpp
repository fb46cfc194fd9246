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
// A NUL would cut what() short, and other control characters garble the
// terminal: show them as escapes. Newlines and tabs stay (wrapped messages).
std::string printable(std::string text) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (char ch : text) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    else out += ch;
  }
  return out;
}

std::vector<Diagnostic> printable(std::vector<Diagnostic> diagnostics) {
  for (auto& d : diagnostics) {
    d.message = printable(std::move(d.message));
    d.where.file = printable(std::move(d.where.file));
  }
  return diagnostics;
}

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
    : std::runtime_error(join_diagnostics(printable(diagnostics))), diagnostics_(printable(std::move(diagnostics))) {}

ParameterError::ParameterError(std::string parameter, std::string message)
    : InputError("parameter '" + parameter + "': " + message),
      parameter_(std::move(parameter)),
      detail_(std::move(message)) {}

InputError::~InputError() = default;
ParameterError::~ParameterError() = default;
RunError::~RunError() = default;

}  // namespace touchcloud
