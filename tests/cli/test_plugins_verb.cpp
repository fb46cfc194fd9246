// `touchcloud plugins` over a folder of hostile plugins: no crash, the good
// ones listed, each bad one reported with its library.
#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace touchcloud;

// `touchcloud plugins` lists the good plugins and reports each bad one.
TEST(PluginDescriptors, PluginsVerbListsTheGoodAndReportsTheBad) {
  const auto r = test::run_cli({"plugins"}, "TOUCHCLOUD_PLUGIN_PATH=" TOUCHCLOUD_TEST_PLUGIN_DIR);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.out.find("test_counter - "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("downsample - "), std::string::npos) << r.out;
  for (const char* bad : {"test_null_name", "test_null_stage", "test_data_entry"})
    EXPECT_NE(r.err.find(std::string("touchcloud_") + bad + ".so"), std::string::npos) << bad << "\n" << r.err;
}
