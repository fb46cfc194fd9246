// `touchcloud plugins` over a folder of hostile plugins: no crash, the good
// ones listed, each bad one reported with its library; the shipped plugins
// grouped by category; one plugin's metrics and artifact roles.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "touchcloud/plugin.hpp"

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

// `touchcloud plugins` heads each category's plugins, in PluginCategory's
// order; --json lists them by name, each with its category.
TEST(PluginsVerb, ListsThePluginsGroupedByCategory) {
  const auto text = test::run_cli({"plugins"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const auto listed = test::run_cli({"plugins", "--json"});
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  const auto plugins = nlohmann::json::parse(listed.out);
  ASSERT_GT(plugins.size(), 30u);

  std::map<std::string, std::string> heading_of;  // plugin -> the heading above it
  std::vector<std::string> headings;
  std::istringstream lines(text.out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("== ", 0) == 0 && line.size() > 6) {
      headings.push_back(line.substr(3, line.size() - 6));
    } else if (const auto dash = line.find(" - "); dash != std::string::npos && line[0] != ' ' && !headings.empty()) {
      heading_of[line.substr(0, dash)] = headings.back();
    }
  }
  std::vector<std::string> names;
  for (const auto& p : plugins) {
    std::string title = p.at("category").get<std::string>();
    std::replace(title.begin(), title.end(), '_', ' ');
    EXPECT_EQ(heading_of[p.at("name").get<std::string>()], title) << p.at("name");
    names.push_back(p.at("name").get<std::string>());
  }
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(heading_of.size(), names.size()) << "every plugin under a heading";
  // Each category once, in PluginCategory's order.
  std::vector<std::string> enum_order;
  for (const PluginCategory c : kPluginCategories)
    if (std::find(headings.begin(), headings.end(), category_title(c)) != headings.end())
      enum_order.push_back(category_title(c));
  EXPECT_EQ(headings, enum_order);
  EXPECT_EQ(heading_of["checkerboard_press"], "simulation");
  EXPECT_EQ(heading_of["chamfer"], "scoring");
  EXPECT_EQ(heading_of["next_touch"], "planning");
}

// One plugin's page lists its metrics (unit, doc, when, direction, role)
// and the roles of what it writes.
TEST(PluginsVerb, OnePluginsPageListsItsMetricsAndArtifactRoles) {
  const auto r = test::run_cli({"plugins", "chamfer"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  category: scoring\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  metrics:\n"), std::string::npos) << r.out;
  // A metric's two lines: name, unit and traits; its doc beneath.
  const auto lines_of = [&](const std::string& start) {
    const auto at = r.out.find("\n    " + start + " ");
    if (at == std::string::npos) return std::string();
    return r.out.substr(at + 1, r.out.find('\n', r.out.find('\n', at + 1) + 1) - at - 1);
  };
  const std::string eq11 = lines_of("chamfer_est_to_gt");
  for (const char* part : {" mm ", " per item, lower is better, role accuracy\n", "(Eq. 11)"})
    EXPECT_NE(eq11.find(part), std::string::npos) << part << " in: " << eq11;
  EXPECT_NE(lines_of("final_chamfer_mm").find(" final, lower is better\n"), std::string::npos) << r.out;
  EXPECT_NE(lines_of("final_fscore").find(" final, higher is better\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  writes:\n    ground_truth "), std::string::npos) << r.out;
}
