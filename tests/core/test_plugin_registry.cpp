// Finding and loading plugins: search path, failures and ABI checks.
#include <gtest/gtest.h>

#include <cstdlib>

#include "stage_harness.hpp"
#include "test_support.hpp"
#include "touchcloud/plugin_registry.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

TEST(PluginRegistry, FindsBuiltInPluginsBesideTheCoreLibrary) {
  PluginRegistry registry;
  const auto names = registry.available();
  for (const char* name : {"cloud_reader", "cloud_writer", "downsample"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  const LoadedPlugin& p = registry.load("downsample");
  EXPECT_EQ(p.name(), "downsample");
  EXPECT_FALSE(p.description().empty());
  EXPECT_EQ(p.toolkit_version(), kVersion);
  // The schema comes from the plugin's own declaration.
  const auto& params = p.schema().parameters;
  ASSERT_FALSE(params.empty());
  EXPECT_TRUE(std::any_of(params.begin(), params.end(),
                          [](const ParamSpec& s) { return s.name == "leaf_size_mm" && s.unit == "mm"; }));
  EXPECT_EQ(p.schema().inputs.at(0).type, "point_cloud");
}

TEST(PluginRegistry, UnknownPluginSuggestsNearestNameAndListsFolders) {
  auto registry = test::test_registry();
  try {
    registry.load("downsampel");
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("unknown plugin 'downsampel'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'downsample'?"), std::string::npos) << msg;
    for (const auto& folder : registry.search_path()) EXPECT_NE(msg.find(folder.string()), std::string::npos) << msg;
  }
}

TEST(PluginRegistry, AbiMismatchNamesBothVersions) {
  auto registry = test::test_registry();
  try {
    registry.load("test_old_abi");
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("ABI version 0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("ABI version " + std::to_string(kPluginAbiVersion)), std::string::npos) << msg;
    EXPECT_NE(msg.find("test_old_abi"), std::string::npos) << msg;
  }
}

TEST(PluginRegistry, LoadFailureSaysPluginFoldersAndLoaderError) {
  auto registry = test::test_registry();
  try {
    registry.load("test_unloadable");
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("plugin 'test_unloadable' failed to load"), std::string::npos) << msg;
    EXPECT_NE(msg.find("touchcloud_symbol_that_does_not_exist"), std::string::npos) << "dlerror text: " << msg;
    EXPECT_NE(msg.find("folders searched"), std::string::npos) << msg;
    EXPECT_NE(msg.find(TOUCHCLOUD_TEST_PLUGIN_DIR), std::string::npos) << msg;
  }
}

TEST(PluginRegistry, LibraryWithoutEntryPointIsRefused) {
  test::TempDir dir;
  // A real shared library that is not a plugin: copy the core library.
  const fs::path core = test::binary_dir() / "lib";
  fs::path source;
  for (const auto& f : fs::directory_iterator(core))
    if (f.path().filename().string().rfind("libtouchcloud_core.so", 0) == 0 && !fs::is_symlink(f)) source = f.path();
  ASSERT_FALSE(source.empty());
  fs::copy_file(source, dir / "touchcloud_impostor.so");
  PluginRegistry registry({dir.path()});
  try {
    registry.load("impostor");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a touchcloud plugin"), std::string::npos) << e.what();
  }
}

TEST(PluginRegistry, EnvironmentFoldersComeAfterBuiltInOnes) {
  ::setenv("TOUCHCLOUD_PLUGIN_PATH", (std::string(TOUCHCLOUD_TEST_PLUGIN_DIR) + ":/nonexistent/folder").c_str(), 1);
  const auto path = PluginRegistry::default_search_path();
  ::unsetenv("TOUCHCLOUD_PLUGIN_PATH");
  ASSERT_GE(path.size(), 3u);
  EXPECT_EQ(path[path.size() - 2], fs::weakly_canonical(TOUCHCLOUD_TEST_PLUGIN_DIR));
  EXPECT_EQ(path.back(), fs::path("/nonexistent/folder"));
  EXPECT_EQ(path.front(), fs::weakly_canonical(test::binary_dir() / "lib/touchcloud/plugins"));
}

TEST(PluginRegistry, RejectsNamesThatAreNotIdentifiers) {
  PluginRegistry registry;
  EXPECT_THROW(registry.load("../etc/passwd"), InputError);
}

// The CLI reports an error after the pipeline, and with it the plugin that
// threw it, is gone: the error's type and message must not live in the
// plugin's code.
TEST(PluginRegistry, AnErrorAPluginThrowsOutlivesThePlugin) {
  for (const std::string kind : {"input", "run"}) {
    std::exception_ptr thrown;
    {
      test::StageHarness stage("test_throwing", {{"error", kind}});
      stage.configure();
      try {
        stage.process({}, {"value"});
      } catch (...) {
        thrown = std::current_exception();
      }
    }  // the harness's registry unloads the library here
    ASSERT_TRUE(thrown) << kind;
    try {
      std::rethrow_exception(thrown);
    } catch (const InputError& e) {
      EXPECT_EQ(kind, "input");
      EXPECT_STREQ(e.what(), "the gel tore (simulated failure)");
    } catch (const RunError& e) {
      EXPECT_EQ(kind, "run");
      EXPECT_STREQ(e.what(), "the gel tore (simulated failure)");
    }
  }
}
