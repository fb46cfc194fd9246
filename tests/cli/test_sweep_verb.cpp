// touchcloud sweep: the grid, the records, and bad keys refused up front.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

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

// The sweep holds its folder from its first run to its last: a second sweep
// into it is refused at once, and the first one's records stay whole.
TEST(SweepVerb, ASecondSweepIntoAFolderInUseIsRefused) {
  touchcloud::test::TempDir dir;
  write_file(dir / "slow.yaml", counting_pipeline("step: 1, check_ms: 1500"));
  write_file(dir / "p.yaml", counting_pipeline());
  const fs::path out = dir / "sw";
  const pid_t first = ::fork();
  if (first == 0) {
    ::setenv("TOUCHCLOUD_PLUGIN_PATH", TOUCHCLOUD_TEST_PLUGIN_DIR, 1);
    const std::string pipeline = (dir / "slow.yaml").string();
    ::execl(touchcloud::test::cli_path().c_str(), "touchcloud", "sweep", pipeline.c_str(), "--vary", "c.step=1,2,3",
            "--out", out.c_str(), "--accuracy", "c.value", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // runs/ appears once the first sweep holds the folder, before its first run.
  for (int i = 0; i < 600 && !fs::exists(out / "runs"); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(fs::exists(out / "runs"));
  const auto second = run_cli({"sweep", (dir / "p.yaml").string(), "--vary", "c.step=5", "--out", out.string(),
                               "--accuracy", "c.value"},
                              kTestPlugins);
  EXPECT_EQ(second.exit_code, 2) << second.err;
  EXPECT_NE(second.err.find("touchcloud: error: the output folder " + out.string() + " is in use"), std::string::npos)
      << second.err;
  int status = 0;
  ASSERT_EQ(::waitpid(first, &status, 0), first);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const auto rows = read_csv(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 4u);
  const std::size_t error = column(rows[0], "error");
  for (std::size_t i = 1; i < rows.size(); ++i)
    EXPECT_TRUE(rows[i].size() <= error || rows[i][error].empty()) << "run " << i << " failed: " << rows[i][error];
}

// An output folder that cannot be made is bad input with one clear line, as for `run`.
TEST(SweepVerb, AnOutputFolderThatCannotBeMadeIsBadInput) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml", counting_pipeline());
  write_file(dir / "file", "a regular file");
  const auto r = run_cli({"sweep", (dir / "p.yaml").string(), "--vary", "c.step=1", "--out", (dir / "file/sw").string(),
                          "--accuracy", "c.value"},
                         kTestPlugins);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("touchcloud: error: cannot create the output folder " + (dir / "file/sw").string()),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("filesystem error"), std::string::npos) << r.err;
}

// --resume refuses a sweep.csv whose rows are corrupt (a NaN, a word for a
// seed), naming the file and line, and reads one saved with CRLF line ends
// and a byte order mark as it reads its own.
TEST(SweepVerb, ResumeRefusesCorruptRowsAndReadsWindowsLineEnds) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml", counting_pipeline());
  const auto sweep = [&](const std::string& out) {
    return run_cli({"sweep", (dir / "p.yaml").string(), "--vary", "c.step=0.5,2", "--out", (dir / out).string(),
                    "--accuracy", "c.value", "--resume"},
                   kTestPlugins);
  };
  ASSERT_EQ(sweep("whole").exit_code, 0);
  const auto rows = read_csv(dir / "whole/sweep.csv");
  ASSERT_EQ(rows.size(), 3u);
  const auto line = [&](std::vector<std::string> cells) {
    cells.resize(rows[0].size());  // read_csv drops an empty last cell (the error)
    std::string text;
    for (const auto& c : cells) text += (&c == &cells[0] ? "" : ",") + c;
    return text;
  };
  auto nan_row = rows[2], word_seed = rows[2];
  nan_row[column(rows[0], "c.value")] = "nan";
  word_seed[column(rows[0], "seed")] = "x";
  for (const auto& [name, row] : std::vector<std::pair<std::string, std::vector<std::string>>>{{"nan", nan_row},
                                                                                                {"seed", word_seed}}) {
    fs::create_directories(dir / name);
    write_file(dir / name / "sweep.csv", line(rows[0]) + "\n" + line(rows[1]) + "\n" + line(row) + "\n");
    const auto r = sweep(name);
    EXPECT_EQ(r.exit_code, 2) << name << ": " << r.err;
    EXPECT_NE(r.err.find((dir / name / "sweep.csv").string() + ":3"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(name == "nan" ? "c.value is 'nan', not a finite number" : "seed is 'x', not a whole number"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / name / "sweep_summary.csv"));
  }
  fs::create_directories(dir / "crlf");
  write_file(dir / "crlf/sweep.csv", "\xEF\xBB\xBF" + line(rows[0]) + "\r\n" + line(rows[1]) + "\r\n");
  const auto r = sweep("crlf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1 of them from before (--resume)"), std::string::npos) << r.out;
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
