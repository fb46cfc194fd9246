// Background stages (`background: true`): they overlap the stages after
// them, and change nothing else: the same results in the same order, errors
// named as before, outputs read by any later stage.
#include <nlohmann/json.hpp>

#include "pipeline_fixture.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

class BackgroundStages : public touchcloud::test::PipelineFixture {
 protected:
  RunResult run(const std::string& yaml, const fs::path& out = {}) {
    Pipeline p = load(yaml);
    RunOptions o;
    o.seed = 3;
    o.out_dir = out;
    o.quiet = true;
    return run_pipeline(p, o);
  }
  static const std::vector<double>& series(const RunResult& r, const std::string& key) {
    return r.record.metrics.at(key).values;
  }
};

// `yaml` with every `background: BG` set to `value`.
std::string with_background(std::string yaml, bool value) {
  for (auto at = yaml.find("BG"); at != std::string::npos; at = yaml.find("BG"))
    yaml.replace(at, 2, value ? "true" : "false");
  return yaml;
}

// A chain through both kinds of stage: f (foreground) reads b's value from
// the previous iteration; b (background) reads f; d (background) reads b;
// after the loop, `last` (foreground) reads d.
const std::string kChain =
    "stages:\n  - id: l\n    loop:\n      max_iterations: 6\n      stages:\n"
    "        - id: f\n          plugin: test_counter\n          params: {step: 1}\n"
    "          inputs: {previous: b.value@previous}\n"
    "        - id: b\n          plugin: test_counter\n          background: BG\n          params: {step: 10}\n"
    "          inputs: {previous: f.value}\n"
    "        - id: d\n          plugin: test_counter\n          background: BG\n          params: {step: 50}\n"
    "          inputs: {previous: b.value}\n"
    "  - id: last\n    plugin: test_counter\n    params: {step: 100}\n    inputs: {previous: d.value}\n";

}  // namespace

TEST_F(BackgroundStages, GiveTheSameResultsAsInTheForeground) {
  const RunResult fg = run(with_background(kChain, false));
  const RunResult bg = run(with_background(kChain, true));
  EXPECT_EQ(series(bg, "f.value"), (std::vector<double>{1, 12, 23, 34, 45, 56}));
  EXPECT_EQ(series(bg, "b.value"), (std::vector<double>{11, 22, 33, 44, 55, 66}));
  EXPECT_EQ(series(bg, "d.value"), (std::vector<double>{61, 72, 83, 94, 105, 116}));
  EXPECT_EQ(series(bg, "last.value"), (std::vector<double>{216}));
  for (const auto& [key, s] : fg.record.metrics) EXPECT_EQ(series(bg, key), s.values) << key;
  for (const auto& t : bg.timings) EXPECT_EQ(t.calls, t.id == "last" ? 1 : 6) << t.id;
}

TEST_F(BackgroundStages, OverlapTheStagesAfterThem) {
  // w's n-th call waits for s's n-th call, which comes after it: only a
  // background w lets s run meanwhile.
  const std::string yaml =
      "stages:\n  - id: l\n    loop:\n      max_iterations: 4\n      stages:\n"
      "        - id: w\n          plugin: test_rendezvous\n          background: BG\n"
      "          params: {role: wait, timeout_ms: TIMEOUT}\n"
      "        - id: s\n          plugin: test_rendezvous\n          params: {role: signal}\n";
  const auto with_timeout = [](std::string y, const std::string& ms) { return y.replace(y.find("TIMEOUT"), 7, ms); };
  const RunResult r = run(with_timeout(with_background(yaml, true), "30000"));
  EXPECT_EQ(r.loop_iterations.at(0).second, 4);
  try {
    run(with_timeout(with_background(yaml, false), "200"));
    FAIL() << "a waiting stage in the foreground should time out";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("no signal for call 1"), std::string::npos) << e.what();
  }
}

TEST_F(BackgroundStages, AFailureEndsTheRunNamingStageAndIterationAndLeavesNoOutput) {
  const fs::path out = dir_ / "out";
  try {
    run("stages:\n  - id: l\n    loop:\n      max_iterations: 50\n      stages:\n"
        "        - id: c\n          plugin: test_counter\n"
        "        - id: bad\n          plugin: test_throwing\n          background: true\n          params: {fail_at: 2}\n",
        out);
    FAIL() << "no error";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("stage 'bad' (plugin test_throwing) failed in process in iteration 2: the gel tore"),
              std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(BackgroundStages, AFailureReachesTheStagesThatReadTheFailedCall) {
  // `c` reads the failed call's output at once: the run reports the
  // background stage's error, not a missing input.
  try {
    run("stages:\n  - id: bad\n    plugin: test_throwing\n    background: true\n"
        "  - id: c\n    plugin: test_counter\n    inputs: {previous: bad.value}\n");
    FAIL() << "no error";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("stage 'bad' (plugin test_throwing) failed in process: the gel tore"),
              std::string::npos) << e.what();
  }
}

TEST_F(BackgroundStages, CanEndALoop) {
  const RunResult r = run(
      "stages:\n  - id: l\n    loop:\n      max_iterations: 30\n      until: c.done\n      stages:\n"
      "        - id: c\n          plugin: test_counter\n          background: true\n          params: {stop_at: 3}\n");
  EXPECT_EQ(r.loop_iterations.at(0).second, 3);
  EXPECT_EQ(series(r, "c.value").size(), 3u);
}

TEST_F(BackgroundStages, AreMarkedInTheSummary) {
  const fs::path out = dir_ / "out";
  run(with_background(kChain, true), out);
  const auto j = nlohmann::json::parse(touchcloud::test::read_file(out / "summary.json"));
  std::map<std::string, bool> background;
  for (const auto& s : j["stages"]) background[s["id"]] = s.value("background", false);
  EXPECT_EQ(background, (std::map<std::string, bool>{{"f", false}, {"b", true}, {"d", true}, {"last", false}}));
}

TEST_F(BackgroundStages, TheKeyIsTrueOrFalse) {
  const auto d = errors("stages:\n  - id: c\n    plugin: test_counter\n    background: sometimes\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(touchcloud::test::mentions(d[0], "'background' is true or false")) << d[0].message;
  EXPECT_EQ(d[0].where.line, 4);
}
