// touchcloud sweep: the grid, the records, and bad keys refused up front.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "counting_pipeline.hpp"
#include "test_support.hpp"

using touchcloud::test::read_file;
using touchcloud::test::run_cli;
using touchcloud::test::write_file;
namespace fs = std::filesystem;

namespace {
const std::string kTestPlugins = "TOUCHCLOUD_PLUGIN_PATH=" TOUCHCLOUD_TEST_PLUGIN_DIR;

using touchcloud::test::counting_pipeline;

std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(read_file(file));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  EXPECT_NE(it, header.end()) << name;
  return static_cast<std::size_t>(it - header.begin());
}
}  // namespace

TEST(SweepVerb, RunsEveryCombinationAndRepeat) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml", counting_pipeline());
  const auto r = run_cli({"sweep", (dir / "p.yaml").string(), "--vary", "c.step=0.5,2", "--vary",
                          "l.max_iterations=1,3", "--repeats", "2", "--seed", "10", "--out", (dir / "sw").string(),
                          "--accuracy", "c.value"},
                         kTestPlugins);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_csv(dir / "sw/sweep.csv");
  ASSERT_EQ(rows.size(), 1u + 2 * 2 * 2);
  const auto& h = rows[0];
  const std::size_t step = column(h, "c.step"), iters = column(h, "l.max_iterations"), value = column(h, "c.value"),
                    seed = column(h, "seed");
  column(h, "wall_time_s");
  column(h, "time_c_s");
  for (std::size_t i = 1; i < rows.size(); ++i)
    EXPECT_DOUBLE_EQ(std::stod(rows[i][value]), std::stod(rows[i][step]) * std::stod(rows[i][iters])) << i;
  EXPECT_EQ(rows[1][seed], "10");
  EXPECT_EQ(rows[2][seed], "11");
  const auto summary = read_csv(dir / "sw/sweep_summary.csv");
  ASSERT_EQ(summary.size(), 1u + 4);
  EXPECT_EQ(summary[0][column(summary[0], "runs")], "runs");
  EXPECT_TRUE(fs::exists(dir / "sw/runs/setting3_seed11/summary.json"));
  // The plot needs matplotlib; without it the verb says so and keeps the CSVs.
  if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") == 0) {
    EXPECT_TRUE(fs::exists(dir / "sw/accuracy_vs_time.png")) << r.out;
    EXPECT_TRUE(fs::exists(dir / "sw/accuracy_vs_time.svg"));
  } else {
    EXPECT_NE(r.out.find("no plot"), std::string::npos) << r.out;
  }
}

TEST(SweepVerb, BadKeysAndValuesFailBeforeAnythingRuns) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml", counting_pipeline());
  const std::string p = (dir / "p.yaml").string(), out = (dir / "sw").string();
  auto r = run_cli({"sweep", p, "--vary", "c.stepp=1,2", "--out", out}, kTestPlugins);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--vary c.stepp=1: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'step'?"), std::string::npos) << r.err;
  r = run_cli({"sweep", p, "--vary", "nosuch.step=1", "--out", out}, kTestPlugins);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no stage with id 'nosuch'"), std::string::npos) << r.err;
  r = run_cli({"sweep", p, "--vary", "c.step=1,big", "--out", out}, kTestPlugins);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--vary c.step=big"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected a number"), std::string::npos) << r.err;
  r = run_cli({"sweep", p, "--vary", "c.step", "--out", out}, kTestPlugins);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "sw")) << "nothing is written when a setting is bad";
}

// Without --accuracy the plot takes the metric a stage declares with role
// accuracy, whatever its name; an --accuracy no stage declares is refused
// before anything runs.
TEST(SweepVerb, PlotsTheMetricOfRoleAccuracyAndRefusesAnUndeclaredOne) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml",
             "stages:\n  - id: l\n    loop:\n      max_iterations: 2\n      stages:\n"
             "        - id: s\n          plugin: test_declared_outputs\n"
             "        - id: c\n          plugin: test_counter\n");
  const std::string p = (dir / "p.yaml").string();
  auto r = run_cli({"sweep", p, "--vary", "c.step=1,2", "--out", (dir / "sw").string()}, kTestPlugins);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") == 0) {
    EXPECT_NE(r.out.find("plotted s.error_mm against wall_time_s"), std::string::npos) << r.out;
  }
  r = run_cli({"sweep", p, "--vary", "c.step=1,2", "--accuracy", "s.surprise", "--out", (dir / "sw2").string()},
              kTestPlugins);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--accuracy s.surprise: no stage of the pipeline declares such a metric (s.error_mm, s.calls, "
                       "c.value, "),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "sw2/runs")) << "nothing ran";
}
