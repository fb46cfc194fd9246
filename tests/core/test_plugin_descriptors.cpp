// Hostile plugin descriptors: the loader refuses each, naming the library and
// why, instead of crashing (tests/support/plugins builds them).
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/plugin_registry.hpp"

using namespace touchcloud;

namespace {
std::string load_error(const std::string& name) {
  auto registry = test::test_registry();
  try {
    registry.load(name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded)";
}
}  // namespace

TEST(PluginDescriptors, NullNameIsRefusedWithThePath) {
  const std::string msg = load_error("test_null_name");
  EXPECT_NE(msg.find("touchcloud_test_null_name.so"), std::string::npos) << msg;
  EXPECT_NE(msg.find("has no name (NULL)"), std::string::npos) << msg;
}

TEST(PluginDescriptors, CreateReturningNullIsRefused) {
  const std::string msg = load_error("test_null_stage");
  EXPECT_NE(msg.find("touchcloud_test_null_stage.so"), std::string::npos) << msg;
  EXPECT_NE(msg.find("create() returned no stage"), std::string::npos) << msg;
}

TEST(PluginDescriptors, DataSymbolAsEntryPointIsRefused) {
  const std::string msg = load_error("test_data_entry");
  EXPECT_NE(msg.find("touchcloud_test_data_entry.so"), std::string::npos) << msg;
  EXPECT_NE(msg.find("as data, not as the function"), std::string::npos) << msg;
}

TEST(PluginDescriptors, CategoryOutsideTheEnumIsRefused) {
  const std::string msg = load_error("test_unknown_category");
  EXPECT_NE(msg.find("touchcloud_test_unknown_category.so"), std::string::npos) << msg;
  EXPECT_NE(msg.find("category (99) is none of touchcloud's"), std::string::npos) << msg;
}
