// Every pipeline in pipelines/ loads and validates as shipped: the plugins,
// parameters, input files and wiring it names all exist.
#include <gtest/gtest.h>

#include <algorithm>

#include "test_support.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

TEST(ShippedPipelines, EveryPipelineValidates) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "pipelines"))
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 9u);
  PluginRegistry registry;
  for (const auto& file : files) {
    try {
      Pipeline::load(file, {}, registry);
    } catch (const InputError& e) {
      ADD_FAILURE() << file.filename() << ": " << e.what();
    }
  }
}
