// Writes a pipeline into a temporary folder and loads it with the test plugins.
#pragma once

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace touchcloud::test {

class PipelineFixture : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& yaml, const std::string& name = "p.yaml") {
    const auto file = dir_ / name;
    write_file(file, yaml);
    return file;
  }
  Pipeline load(const std::string& yaml, const std::vector<Override>& overrides = {}) {
    return Pipeline::load(write(yaml), overrides, registry_);
  }
  // The diagnostics that loading `yaml` gives; fails the test when it loads.
  std::vector<Diagnostic> errors(const std::string& yaml, const std::vector<Override>& overrides = {}) {
    try {
      load(yaml, overrides);
    } catch (const InputError& e) {
      return e.diagnostics();
    }
    ADD_FAILURE() << "pipeline loaded without errors:\n" << yaml;
    return {};
  }
  TempDir dir_;
  PluginRegistry registry_ = test_registry();
};

inline bool mentions(const Diagnostic& d, const std::string& text) {
  return d.message.find(text) != std::string::npos;
}

}  // namespace touchcloud::test
