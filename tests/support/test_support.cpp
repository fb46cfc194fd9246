#include "test_support.hpp"

#include <gtest/gtest.h>

#include "touchcloud/error.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace touchcloud::test {

fs::path source_dir() { return TOUCHCLOUD_SOURCE_DIR; }
fs::path binary_dir() { return TOUCHCLOUD_BINARY_DIR; }
fs::path cli_path() { return binary_dir() / "bin" / "touchcloud"; }
std::string gel_dome_cloud() { return (source_dir() / "sample_clouds" / "gel_dome.pcd").string(); }

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = fs::temp_directory_path() /
          ("touchcloud-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(path_);
  fs::create_directories(path_);
}
TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void write_file(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string input_error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

std::string printed_on_stderr(const std::function<void()>& run) {
  testing::internal::CaptureStderr();
  run();
  return testing::internal::GetCapturedStderr();
}

PluginRegistry test_registry() {
  auto path = PluginRegistry::default_search_path();
  path.push_back(TOUCHCLOUD_TEST_PLUGIN_DIR);
  return PluginRegistry(path);
}

namespace {
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

CliResult run_cli(const std::vector<std::string>& args, const std::string& env) {
  return run_program(cli_path(), args, env);
}

CliResult run_program(const fs::path& program, const std::vector<std::string>& args, const std::string& env) {
  TempDir io;
  std::string cmd = env + (env.empty() ? "" : " ") + quote(program.string());
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " >" + quote((io / "out").string()) + " 2>" + quote((io / "err").string());
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(io / "out");
  r.err = read_file(io / "err");
  return r;
}

}  // namespace touchcloud::test
