// Every pipeline in pipelines/ loads and validates as shipped: the plugins,
// parameters, input files and wiring it names all exist.
#include <gtest/gtest.h>

#include <algorithm>

#include "test_support.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

#ifdef TOUCHCLOUD_WITHOUT_NETWORKS
namespace {
bool read_network_plugins(const fs::path& file) {
  const std::string text = test::read_file(file);
  return text.find("plugin: gs_depthnet") != std::string::npos || text.find("plugin: tactile_net") != std::string::npos;
}
}  // namespace
#endif

TEST(ShippedPipelines, EveryPipelineValidates) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "pipelines"))
    if (entry.path().extension() == ".yaml") {
#ifdef TOUCHCLOUD_WITHOUT_NETWORKS
      // Built without the learning library: the network pipelines name plugins this build lacks.
      if (read_network_plugins(entry.path())) continue;
#endif
      files.push_back(entry.path());
    }
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
