// Shared test helpers: paths, temporary folders, pipelines written on the fly,
// and running the CLI as a user would.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "touchcloud/pipeline.hpp"

namespace touchcloud::test {

std::filesystem::path source_dir();
std::filesystem::path binary_dir();
std::filesystem::path cli_path();  // build/bin/touchcloud
// sample_clouds/gel_dome.pcd: the small cloud the pipeline tests read.
std::string gel_dome_cloud();

// A fresh empty folder under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

void write_file(const std::filesystem::path& file, const std::string& text);
std::string read_file(const std::filesystem::path& file);

// The message of the InputError `read` throws, or "(no InputError)".
std::string input_error_of(const std::function<void()>& read);

// What `run` printed on stderr (file descriptor 2, as a library prints).
std::string printed_on_stderr(const std::function<void()>& run);

// The default search path plus the folder of test-only plugins.
PluginRegistry test_registry();

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};
// Runs build/bin/touchcloud with `args` (shell-quoted here) and `env` prefix.
CliResult run_cli(const std::vector<std::string>& args, const std::string& env = "");
// The same for another program of the build (build/bin/NAME).
CliResult run_program(const std::filesystem::path& program, const std::vector<std::string>& args,
                      const std::string& env = "");

}  // namespace touchcloud::test
