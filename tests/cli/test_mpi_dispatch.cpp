// `mpirun -n 2 touchcloud sweep|score` writes what one rank writes (times,
// rank and host aside), and so does -n 4; a failing run is a row with its
// error; --resume runs only what a stopped sweep left out. Skipped where
// mpirun is absent. TOUCHCLOUD_TEST_MPI_RANKS=N runs the 2-rank tests on N
// ranks instead.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cloud_files.hpp"
#include "counting_pipeline.hpp"
#include "test_support.hpp"

using touchcloud::test::read_file;
using touchcloud::test::run_cli;
using touchcloud::test::run_program;
using touchcloud::test::TempDir;
using touchcloud::test::write_file;
namespace fs = std::filesystem;

namespace {
const std::string kTestPlugins = "TOUCHCLOUD_PLUGIN_PATH=" TOUCHCLOUD_TEST_PLUGIN_DIR;

// The counter adds `step` per iteration; each load takes check_ms (a run of
// ~0.1 s, so that both ranks get runs); random_draw depends on the seed.
std::string counting_pipeline() { return touchcloud::test::counting_pipeline("step: 1, check_ms: 100"); }

// mpirun's path, or "" where it is absent or the CLI was built without MPI.
std::string mpirun() {
#if !TOUCHCLOUD_TEST_MPI
  return "";
#else
  return std::system("command -v mpirun >/dev/null 2>&1") == 0 ? "mpirun" : "";
#endif
}
#define SKIP_WITHOUT_MPIRUN()                                                                                 \
  if (mpirun().empty())                                                                                       \
  GTEST_SKIP() << "needs mpirun and a build with -DTOUCHCLOUD_MPI=ON (apt-get install libopenmpi-dev "     \
                  "openmpi-bin; scripts/install-deps.sh installs both)"

// The ranks of the tests below: 2, or TOUCHCLOUD_TEST_MPI_RANKS.
int test_ranks() {
  const char* n = std::getenv("TOUCHCLOUD_TEST_MPI_RANKS");
  return n && std::atoi(n) >= 2 ? std::atoi(n) : 2;
}

// `mpirun -n RANKS touchcloud ARGS` (as root too; more ranks than cores).
touchcloud::test::CliResult run_on_ranks(int ranks, const std::vector<std::string>& args, const std::string& env = "") {
  std::vector<std::string> all = {"-n", std::to_string(ranks), "--oversubscribe", "--allow-run-as-root",
                                  touchcloud::test::cli_path().string()};
  all.insert(all.end(), args.begin(), args.end());
  return run_program("mpirun", all, env);
}
touchcloud::test::CliResult run_on_test_ranks(const std::vector<std::string>& args, const std::string& env = "") {
  return run_on_ranks(test_ranks(), args, env);
}

// "0", "1", ... "n-1".
std::set<std::string> rank_names(int n) {
  std::set<std::string> names;
  for (int r = 0; r < n; ++r) names.insert(std::to_string(r));
  return names;
}

std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
  return cells;
}

// The CSV without the columns that may differ between runs: times, rank, host.
std::string without_times(const fs::path& file, std::set<std::string>* ranks = nullptr) {
  std::istringstream in(read_file(file));
  std::string line, out;
  std::getline(in, line);
  const auto header = csv_cells(line);
  std::vector<bool> keep;
  for (const auto& h : header) {
    const bool time = h.rfind("wall_time_s", 0) == 0 || h.rfind("time_", 0) == 0;
    keep.push_back(!time && h != "rank" && h != "host");
  }
  for (bool first = true; first || std::getline(in, line); first = false) {
    const auto cells = first ? header : csv_cells(line);
    EXPECT_EQ(cells.size() + (line.back() == ',' ? 1 : 0), header.size()) << line;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (keep[i]) out += cells[i] + ",";
      if (!first && ranks && header[i] == "rank") ranks->insert(cells[i]);
    }
    out += "\n";
  }
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

// A sweep of 4 settings x `repeats` seeds on `ranks` ranks writes what one
// rank writes; every rank ran some of the runs (each takes 0.1 s).
void expect_sweep_on_ranks_as_on_one(int ranks, int repeats) {
  TempDir dir;
  write_file(dir / "p.yaml", counting_pipeline());
  const auto sweep = [&](const std::string& out) {
    return std::vector<std::string>{"sweep", (dir / "p.yaml").string(), "--vary", "c.step=0.5,2", "--vary",
                                    "l.max_iterations=1,3", "--repeats", std::to_string(repeats), "--seed", "7",
                                    "--out", (dir / out).string(), "--accuracy", "c.value"};
  };
  const auto one = run_cli(sweep("one"), kTestPlugins);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto many = run_on_ranks(ranks, sweep("many"), kTestPlugins);
  ASSERT_EQ(many.exit_code, 0) << many.out << many.err;

  std::set<std::string> ranks_one, ranks_many;
  const std::string a = without_times(dir / "one/sweep.csv", &ranks_one);
  EXPECT_EQ(a, without_times(dir / "many/sweep.csv", &ranks_many));
  EXPECT_NE(a.find("random_draw"), std::string::npos) << "a metric drawn from the seed is compared too";
  EXPECT_EQ(ranks_one, std::set<std::string>{"0"});
  EXPECT_EQ(ranks_many, rank_names(ranks)) << 4 * repeats << " runs of 0.1 s: every rank ran some";
  EXPECT_EQ(without_times(dir / "one/sweep_summary.csv"), without_times(dir / "many/sweep_summary.csv"));
  // Progress on rank 0 covers the runs of every rank; only rank 0 reports.
  const std::string total = "/" + std::to_string(4 * repeats) + "] ";
  EXPECT_EQ(count(many.err, total), static_cast<std::size_t>(4 * repeats)) << many.err;
  EXPECT_EQ(count(many.out, "wrote "), 1u) << many.out;
  EXPECT_TRUE(fs::exists(dir / ("many/runs/setting3_seed" + std::to_string(7 + repeats - 1) + "/summary.json")));
}

TEST(MpiSweep, TwoRanksWriteWhatOneRankWrites) {
  SKIP_WITHOUT_MPIRUN();
  expect_sweep_on_ranks_as_on_one(test_ranks(), 2);
}

// Nothing assumes two ranks: four (more than this machine's cores) write the same.
TEST(MpiSweep, FourRanksWriteWhatOneRankWrites) {
  SKIP_WITHOUT_MPIRUN();
  expect_sweep_on_ranks_as_on_one(4, 3);
}

TEST(MpiSweep, AFailingRunIsARowWithItsErrorAndTheOthersGoOn) {
  SKIP_WITHOUT_MPIRUN();
  TempDir dir;
  write_file(dir / "p.yaml", "stages:\n  - id: c\n    plugin: test_counter\n    params: {check_ms: 100}\n"
                             "  - id: t\n    plugin: test_throwing\n    params: {fail_at: 1}\n");
  const auto r = run_on_test_ranks({"sweep", (dir / "p.yaml").string(), "--vary", "t.fail_at=1,0,2,3", "--out",
                                   (dir / "sw").string(), "--accuracy", "c.value"},
                                  kTestPlugins);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("1 of 4 runs failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("touchcloud: error: setting 1 seed 0: "), std::string::npos) << r.err;
  const std::string csv = read_file(dir / "sw/sweep.csv");
  std::istringstream in(csv);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u) << csv;
  EXPECT_NE(lines[2].find("the gel tore (simulated failure)"), std::string::npos) << csv;
  for (int i : {1, 3, 4}) EXPECT_EQ(lines[i].back(), ',') << "no error: " << lines[i];
  EXPECT_TRUE(fs::exists(dir / "sw/sweep_summary.csv"));
}

// A sweep stopped half way left the first rows; --resume runs only the rest,
// and the result is the whole sweep's.
TEST(MpiSweep, ResumeRunsOnlyWhatAStoppedSweepLeftOut) {
  TempDir dir;
  write_file(dir / "p.yaml", counting_pipeline());
  const auto sweep = [&](const std::string& out) {
    return std::vector<std::string>{"sweep", (dir / "p.yaml").string(), "--vary", "c.step=0.5,2,3", "--repeats",
                                    "2", "--out", (dir / out).string(), "--accuracy", "c.value", "--resume"};
  };
  const auto whole = run_cli(sweep("whole"), kTestPlugins);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  // Rows 1, 2 and 5 of 6 survive, as a checkpoint with a run missing in between.
  std::istringstream in(read_file(dir / "whole/sweep.csv"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 7u);
  fs::create_directories(dir / "half");
  write_file(dir / "half/sweep.csv", lines[0] + "\n" + lines[1] + "\n" + lines[2] + "\n" + lines[5] + "\n");

  const bool ranks = !mpirun().empty();
  const auto rest = ranks ? run_on_test_ranks(sweep("half"), kTestPlugins) : run_cli(sweep("half"), kTestPlugins);
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  EXPECT_EQ(count(rest.err, "/6] "), 3u) << "only the 3 missing runs ran: " << rest.err;
  EXPECT_NE(rest.out.find("3 of them from before (--resume)"), std::string::npos) << rest.out;
  EXPECT_EQ(without_times(dir / "whole/sweep.csv"), without_times(dir / "half/sweep.csv"));
  EXPECT_EQ(without_times(dir / "whole/sweep_summary.csv"), without_times(dir / "half/sweep_summary.csv"));

  // A sweep.csv of another grid is refused, naming the file and line.
  fs::create_directories(dir / "other");
  write_file(dir / "other/sweep.csv", "setting,c.step,seed,wall_time_s,rank,host,error\n0,9,0,1,0,h,\n");
  const auto other = run_cli(sweep("other"), kTestPlugins);
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("other/sweep.csv:2"), std::string::npos) << other.err;
  EXPECT_NE(other.err.find("c.step = 9, but setting 0 of this sweep has 0.5"), std::string::npos) << other.err;
}

// mpirun ends the job when a rank dies; rank 0 names the runs lost with it,
// and --resume runs what sweep.csv does not hold.
TEST(MpiSweep, ARankThatDiesEndsTheJobNamingTheLostRunsAndResumeCompletesIt) {
  SKIP_WITHOUT_MPIRUN();
  TempDir dir;
  write_file(dir / "p.yaml", "stages:\n  - id: c\n    plugin: test_counter\n    params: {check_ms: 300}\n"
                             "  - id: t\n    plugin: test_throwing\n    params: {fail_at: 5}\n");
  const auto sweep = [&](bool resume) {
    std::vector<std::string> a = {"sweep", (dir / "p.yaml").string(), "--vary", "c.step=1,2,3", "--repeats", "2",
                                  "--out", (dir / "sw").string(), "--accuracy", "c.value"};
    if (resume) a.push_back("--resume");
    return a;
  };
  // Rank 1 gets a run while rank 0 runs the first one (0.3 s), and dies in it.
  const auto killed = run_on_test_ranks(sweep(false), kTestPlugins + " TOUCHCLOUD_TEST_KILL_RANK=1");
  EXPECT_NE(killed.exit_code, 0);
  EXPECT_NE(killed.err.find("touchcloud: error: stopped with "), std::string::npos) << killed.err;
  EXPECT_NE(killed.err.find("lost while running: setting "), std::string::npos) << killed.err;
  EXPECT_NE(killed.err.find(" (rank 1, "), std::string::npos) << killed.err;
  EXPECT_NE(killed.err.find("--resume to run the others"), std::string::npos) << killed.err;
  EXPECT_FALSE(fs::exists(dir / "sw/sweep_summary.csv")) << "the job did not finish";

  const auto resumed = run_cli(sweep(true), kTestPlugins);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  std::istringstream in(read_file(dir / "sw/sweep.csv"));
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 1u + 6);
}

// `score` of 7 estimates (one unreadable) on `ranks` ranks prints what one
// rank prints, every metric bit for bit.
void expect_score_on_ranks_as_on_one(int ranks) {
  TempDir dir;
  // A 10 x 10 mm square (two triangles), sampled with a seed on every rank.
  write_file(dir / "square.obj", "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3\nf 1 3 4\n");
  std::vector<std::string> args = {"score", "--gt", (dir / "square.obj").string(), "--samples", "100000", "--seed",
                                   "3", "--json"};
  for (int i = 0; i < 6; ++i) {
    touchcloud::PointCloud c;
    for (int k = 0; k < 50; ++k)
      c.push_back(pcl::PointXYZ(static_cast<float>((k * 7 + i) % 10), static_cast<float>((k * 3) % 10),
                                static_cast<float>(0.1 * (i + 1))));
    const fs::path file = dir / ("est" + std::to_string(i) + ".pcd");
    touchcloud::test::save_pcd(file, c);
    args.push_back(file.string());
  }
  write_file(dir / "empty.pcd", "");
  args.push_back((dir / "empty.pcd").string());  // fails on whichever rank gets it
  const auto one = run_cli(args);
  const auto many = run_on_ranks(ranks, args);
  EXPECT_EQ(one.exit_code, 2) << one.err;
  EXPECT_EQ(many.exit_code, 2) << many.err;
  auto a = nlohmann::json::parse(one.out), b = nlohmann::json::parse(many.out);
  ASSERT_EQ(a.size(), 7u);
  std::set<int> ranks_seen;
  for (auto* all : {&a, &b})
    for (auto& rec : *all) {
      if (all == &b) ranks_seen.insert(rec["rank"].get<int>());
      for (const char* key : {"time_s", "rank", "host"}) rec.erase(key);
      rec["ground_truth"].erase("load_time_s");
    }
  EXPECT_EQ(a.dump(1), b.dump(1));  // every metric, bit for bit
  EXPECT_EQ(a[6]["status"], "error");
  EXPECT_GE(ranks_seen.size(), 2u) << "7 estimates: more than one rank scored some";
  EXPECT_LT(*ranks_seen.rbegin(), ranks);
  EXPECT_NE(many.err.find("1 of 7 estimates could not be scored"), std::string::npos) << many.err;
}

TEST(MpiScore, TwoRanksPrintWhatOneRankPrints) {
  SKIP_WITHOUT_MPIRUN();
  expect_score_on_ranks_as_on_one(test_ranks());
}

TEST(MpiScore, FourRanksPrintWhatOneRankPrints) {
  SKIP_WITHOUT_MPIRUN();
  expect_score_on_ranks_as_on_one(4);
}
