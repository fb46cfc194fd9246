// The two kinds of failure the CLI tells apart: bad input (exit 2) and a
// failure inside a run (exit 1). Bad input carries where it was found.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace touchcloud {

// A place in an input file; line and column are 1-based, 0 when unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string str() const;  // "file:line:col", "file" or "" as far as known
};

struct Diagnostic {
  SourceLocation where;
  std::string message;
  std::string str() const;  // "FILE:LINE:COL: error: message"
};

// The destructors below are defined in libtouchcloud_base so that these
// classes' vtables and type info live there only: an error a plugin throws
// must stay usable after the plugin is unloaded (the CLI reports it after the
// pipeline, and with it the plugin, is gone).

// Bad input: usage, pipeline, scene, data file. Holds one or more diagnostics.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::string message, SourceLocation where = {});
  explicit InputError(std::vector<Diagnostic> diagnostics);
  ~InputError() override;
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

// Bad input attributed to one parameter of the stage that throws it; the
// runtime adds the file position of that parameter's value.
class ParameterError : public InputError {
 public:
  ParameterError(std::string parameter, std::string message);
  ~ParameterError() override;
  const std::string& parameter() const { return parameter_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string parameter_;
  std::string detail_;
};

// A failure while running (numerical, internal); the runtime names the stage.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~RunError() override;
};

}  // namespace touchcloud
