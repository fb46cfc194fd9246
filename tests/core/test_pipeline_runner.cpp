// Running pipelines: order, loops, @previous, seeds, failures and outputs.
#include <tuple>

#include <nlohmann/json.hpp>

#include "pipeline_fixture.hpp"
#include "touchcloud/types/point_cloud.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

class PipelineRunner : public touchcloud::test::PipelineFixture {
 protected:
  RunResult run(const std::string& yaml, std::uint64_t seed = 0, const fs::path& out = {}) {
    Pipeline p = load(yaml);
    RunOptions o;
    o.seed = seed;
    o.out_dir = out;
    o.quiet = true;
    return run_pipeline(p, o);
  }
  static const std::vector<double>& series(const RunResult& r, const std::string& key) {
    return r.record.metrics.at(key).values;
  }
};

TEST_F(PipelineRunner, LoopRunsItsBudgetAndFeedsThePreviousIteration) {
  const RunResult r = run(
      "stages:\n  - id: explore\n    loop:\n      max_iterations: 5\n      stages:\n"
      "        - id: c\n          plugin: test_counter\n          params: {step: 2}\n"
      "          inputs: {previous: c.value@previous}\n");
  EXPECT_EQ(series(r, "c.value"), (std::vector<double>{2, 4, 6, 8, 10}));
  EXPECT_EQ(series(r, "c.calls").at(0), 5);
  ASSERT_EQ(r.loop_iterations.size(), 1u);
  EXPECT_EQ(r.loop_iterations[0], std::make_pair(std::string("explore"), 5));
}

TEST_F(PipelineRunner, UntilStopsTheLoopEarly) {
  const RunResult r = run(
      "stages:\n  - id: explore\n    loop:\n      max_iterations: 30\n      until: c.done\n      stages:\n"
      "        - id: c\n          plugin: test_counter\n          params: {stop_at: 3}\n");
  EXPECT_EQ(r.loop_iterations[0].second, 3);
  EXPECT_EQ(series(r, "c.value").size(), 3u);
}

TEST_F(PipelineRunner, OnlyOutputsThatAreReadMustBeProduced) {
  // Nothing reads c.done: the stage skips it, and the run accepts that.
  RunResult r = run("stages:\n  - id: l\n    loop:\n      max_iterations: 4\n      stages:\n"
                    "        - id: c\n          plugin: test_counter\n");
  EXPECT_EQ(series(r, "c.done_computed").at(0), 0);
  r = run("stages:\n  - id: l\n    loop:\n      max_iterations: 4\n      until: c.done\n      stages:\n"
          "        - id: c\n          plugin: test_counter\n");
  EXPECT_EQ(series(r, "c.done_computed").at(0), 4);
}

// c counts 1, 2, 3, ... within a run of its loop.
const std::string kAccumulate = "          inputs: {previous: c.value@previous}\n";

TEST_F(PipelineRunner, AnOutputReadOnlyAfterItsLoopIsMadeOnTheCallThatEndsTheLoop) {
  // Ended by the stage's own 'until' flag at its third call of 30.
  const std::string after = "  - id: keep\n    plugin: test_counter\n    params: {step: 0}\n    inputs: {previous: c.record}\n";
  RunResult r = run("stages:\n  - id: l\n    loop:\n      max_iterations: 30\n      until: c.done\n      stages:\n"
                    "        - id: c\n          plugin: test_counter\n          params: {stop_at: 3}\n" + kAccumulate + after);
  EXPECT_EQ(series(r, "c.record_computed").at(0), 1);
  EXPECT_EQ(series(r, "keep.value").at(0), 3);
  // Ended by its iteration count: made on the last call.
  r = run("stages:\n  - id: l\n    loop:\n      max_iterations: 4\n      stages:\n"
          "        - id: c\n          plugin: test_counter\n" + kAccumulate + after);
  EXPECT_EQ(series(r, "c.record_computed").at(0), 1);
  EXPECT_EQ(series(r, "keep.value").at(0), 4);
  // Read inside the loop as well: made on every call.
  r = run("stages:\n  - id: l\n    loop:\n      max_iterations: 4\n      stages:\n"
          "        - id: c\n          plugin: test_counter\n" + kAccumulate +
          "        - id: inside\n          plugin: test_counter\n          inputs: {previous: c.record}\n" + after);
  EXPECT_EQ(series(r, "c.record_computed").at(0), 4);
  EXPECT_EQ(series(r, "keep.value").at(0), 4);
  // Read in the outer loop after an inner one: once per run of the inner loop, each run's last value.
  r = run("stages:\n  - id: outer\n    loop:\n      max_iterations: 2\n      stages:\n"
          "        - id: inner\n          loop:\n            max_iterations: 3\n            stages:\n"
          "              - id: c\n                plugin: test_counter\n"
          "                inputs: {previous: c.value@previous}\n"
          "        - id: keep\n          plugin: test_counter\n          params: {step: 0}\n"
          "          inputs: {previous: c.record}\n");
  EXPECT_EQ(series(r, "c.record_computed").at(0), 2);
  EXPECT_EQ(series(r, "keep.value"), (std::vector<double>{3, 3}));
}

TEST_F(PipelineRunner, AnOutputItsLoopEndedWithoutIsAnErrorNeverAnEarlierRunsValue) {
  // The first run of the inner loop makes the record on its last call (3);
  // the second run does not make it. The reader must not get the first
  // run's value.
  try {
    run("stages:\n  - id: outer\n    loop:\n      max_iterations: 2\n      stages:\n"
        "        - id: inner\n          loop:\n            max_iterations: 3\n            stages:\n"
        "              - id: c\n                plugin: test_counter\n"
        "                params: {record_only_at_call: 3}\n"
        "                inputs: {previous: c.value@previous}\n"
        "        - id: keep\n          plugin: test_counter\n          inputs: {previous: c.record}\n");
    FAIL() << "no error";
  } catch (const RunError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("stage 'keep' (plugin test_counter) failed in process in iteration 1: input 'previous' has no "
                       "value: c.record was not produced (its stage produces it only on the call that ends its loop, "
                       "and the loop ended without it)"), std::string::npos) << msg;
  }
}

TEST_F(PipelineRunner, AWiredOutputThatIsNotProducedFailsTheRun) {
  try {
    run("stages:\n  - id: bad\n    plugin: test_throwing\n    params: {fail_at: 99, skip_output: true}\n"
        "  - id: c\n    plugin: test_counter\n    inputs: {previous: bad.value}\n");
    FAIL();
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("stage 'bad' (plugin test_throwing) failed in process: the stage did not "
                                         "produce its output 'value'"), std::string::npos) << e.what();
  }
}

TEST_F(PipelineRunner, NestedLoopsRestartTheirPreviousValues) {
  // The inner loop's first iteration has no previous value each time it
  // starts, so its count restarts at `step` in every outer iteration.
  const RunResult r = run(
      "stages:\n  - id: touches\n    loop:\n      max_iterations: 2\n      stages:\n"
      "        - id: frames\n          loop:\n            max_iterations: 3\n            stages:\n"
      "              - id: f\n                plugin: test_counter\n"
      "                inputs: {previous: f.value@previous}\n");
  EXPECT_EQ(series(r, "f.value"), (std::vector<double>{1, 2, 3, 1, 2, 3}));
}

// `held` keeps its cloud behind its output and copies it when another holder
// is left at its call; `reader` reads the previous iteration's, `last` the
// final one.
const std::string kHeldCloud =
    "stages:\n  - id: explore\n    loop:\n      max_iterations: 5\n      stages:\n"
    "        - id: reader\n          plugin: test_held_cloud\n          inputs: {cloud: held.cloud@previous}\n"
    "        - id: held\n          plugin: test_held_cloud\n"
    "  - id: last\n    plugin: test_held_cloud\n    inputs: {cloud: held.cloud}\n";

TEST_F(PipelineRunner, AStageHoldsTheOnlyReferenceToItsLastOutputWhenItIsCalledAgain) {
  const RunResult r = run(kHeldCloud);
  EXPECT_EQ(series(r, "reader.points_read"), (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(series(r, "last.points_read"), (std::vector<double>{5}));
  EXPECT_EQ(series(r, "held.copies"), (std::vector<double>{0}));
}

TEST_F(PipelineRunner, ACapturedOutputStaysHeldUntilItsStageReplacesIt) {
  // The live view tells a new value by its address: a captured value let go
  // of before the call could hand its address to the next one.
  Pipeline p = load(kHeldCloud);
  RunOptions o;
  o.quiet = true;
  o.capture = {"held.cloud"};
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(series(r, "held.copies"), (std::vector<double>{4}));
  EXPECT_EQ(std::any_cast<CloudConstPtr>(r.captured.at("held.cloud"))->size(), 5u);
}

TEST_F(PipelineRunner, AnOutputKeptFromEveryCallIsCopiedNotChangedUnderTheKeeper) {
  Pipeline p = load(kHeldCloud);
  RunOptions o;
  o.quiet = true;
  o.capture = {"held.cloud"};
  o.capture_every_call = true;
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(series(r, "held.copies"), (std::vector<double>{4}));
  const auto& calls = r.captured_every_call.at("held.cloud");
  ASSERT_EQ(calls.size(), 5u);
  for (std::size_t i = 0; i < calls.size(); ++i)
    EXPECT_EQ(std::any_cast<CloudConstPtr>(calls[i])->size(), i + 1);
}

TEST_F(PipelineRunner, StagesRunInDependencyOrderWhateverTheFileOrder) {
  const RunResult r = run(
      "stages:\n"
      "  - id: second\n    plugin: test_counter\n    params: {step: 10}\n    inputs: {previous: first.value}\n"
      "  - id: first\n    plugin: test_counter\n    params: {step: 1}\n");
  EXPECT_EQ(series(r, "second.value").at(0), 11);
  EXPECT_EQ(r.timings.at(0).id, "first");
}

TEST_F(PipelineRunner, SeedsReproduceAndDifferentSeedsDiffer) {
  const std::string yaml = "stages:\n  - id: a\n    plugin: test_counter\n  - id: b\n    plugin: test_counter\n";
  const double a1 = series(run(yaml, 7), "a.random_draw")[0];
  const double a2 = series(run(yaml, 7), "a.random_draw")[0];
  const double b1 = series(run(yaml, 7), "b.random_draw")[0];
  const double a3 = series(run(yaml, 8), "a.random_draw")[0];
  EXPECT_EQ(a1, a2);
  EXPECT_NE(a1, b1) << "stages draw from their own streams";
  EXPECT_NE(a1, a3);
}

TEST_F(PipelineRunner, AThrowingStageEndsTheRunNamingStageAndIteration) {
  const fs::path out = dir_ / "out";
  try {
    run("stages:\n  - id: l\n    loop:\n      max_iterations: 5\n      stages:\n"
        "        - id: bad\n          plugin: test_throwing\n          params: {fail_at: 2}\n"
        "        - id: c\n          plugin: test_counter\n",
        0, out);
    FAIL() << "no error";
  } catch (const RunError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("stage 'bad' (plugin test_throwing) failed in process in iteration 2: the gel tore"),
              std::string::npos) << msg;
  }
  EXPECT_FALSE(fs::exists(out)) << "a failed run leaves no output folder behind";
}

TEST_F(PipelineRunner, FailedRunKeepsAnExistingFolderUntouched) {
  const fs::path out = dir_ / "out";
  touchcloud::test::write_file(out / "summary.json", "old");
  EXPECT_THROW(run("stages:\n  - id: bad\n    plugin: test_throwing\n", 0, out), RunError);
  EXPECT_EQ(touchcloud::test::read_file(out / "summary.json"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);
}

TEST_F(PipelineRunner, SummaryRecordsParametersSeedVersionsTimesAndMetrics) {
  const fs::path out = dir_ / "out";
  run("pipeline: counting\nstages:\n  - id: l\n    loop:\n      max_iterations: 3\n      stages:\n"
      "        - id: c\n          plugin: test_counter\n          params: {step: 0.5, offsets: [1, 2]}\n"
      "          inputs: {previous: c.value@previous}\n",
      42, out);
  const auto j = nlohmann::json::parse(touchcloud::test::read_file(out / "summary.json"));
  EXPECT_EQ(j["pipeline"]["name"], "counting");
  EXPECT_EQ(j["seed"], 42);
  EXPECT_EQ(j["versions"]["touchcloud"], kVersion);
  EXPECT_EQ(j["versions"]["plugin_abi"], kPluginAbiVersion);
  const auto& stage = j["stages"][0];
  EXPECT_EQ(stage["id"], "c");
  EXPECT_EQ(stage["params"]["step"], 0.5);
  EXPECT_EQ(stage["params"]["offsets"], nlohmann::json::array({1.0, 2.0}));
  EXPECT_EQ(stage["params"]["label"], "a") << "defaults are recorded too";
  EXPECT_EQ(stage["time_s"]["calls"], 3);
  EXPECT_GE(stage["time_s"]["process"].get<double>(), 0.0);
  EXPECT_EQ(j["loops"]["l"]["iterations"], 3);
  EXPECT_EQ(j["metrics"]["c.value"]["series"], nlohmann::json::array({0.5, 1.0, 1.5}));
  EXPECT_EQ(j["metrics"]["c.value"]["value"], 1.5);
  EXPECT_FALSE(fs::exists(out / (".touchcloud-staging-" + std::to_string(::getpid()))));
  EXPECT_EQ(j["overrides"], nlohmann::json::array());
}

// The overrides a run was given are recorded as given, with where they came
// from (a report labels a sweep's runs by its --vary ones).
TEST_F(PipelineRunner, SummaryRecordsTheOverridesAsGiven) {
  Pipeline p = load("stages:\n  - id: c\n    plugin: test_counter\n",
                    {{"c.step", "0.25"}, {"c.offsets", "[1,  2]", "--vary"}});
  RunOptions o;
  o.quiet = true;
  const auto j = nlohmann::json::parse(run_pipeline(p, o).summary_json);
  EXPECT_EQ(j["overrides"], nlohmann::json::parse(R"([{"key": "c.step", "value": "0.25", "origin": "--set"},
                                                      {"key": "c.offsets", "value": "[1,  2]", "origin": "--vary"}])"));
  EXPECT_EQ(j["stages"][0]["params"]["step"], 0.25);
}

// A stage's checks run at load (a scorer reads its ground-truth file
// there): their time is recorded per stage and in the load time, apart from
// the run's wall time.
TEST_F(PipelineRunner, SummaryRecordsCheckAndLoadTimesApartFromTheRun) {
  const fs::path out = dir_ / "out";
  const RunResult r = run("stages:\n  - id: slow\n    plugin: test_counter\n    params: {check_ms: 60}\n"
                          "  - id: quick\n    plugin: test_counter\n",
                          0, out);
  const auto j = nlohmann::json::parse(touchcloud::test::read_file(out / "summary.json"));
  const double slow = j["stages"][0]["time_s"]["check"].get<double>();
  const double quick = j["stages"][1]["time_s"]["check"].get<double>();
  EXPECT_GE(slow, 0.06);
  EXPECT_LT(quick, slow);
  EXPECT_GE(j["load_time_s"].get<double>(), slow + quick);
  EXPECT_EQ(j["load_time_s"].get<double>(), r.load_time_s);
  EXPECT_EQ(j["wall_time_s"].get<double>(), r.wall_time_s);
  ASSERT_EQ(r.timings.size(), 2u);
  EXPECT_EQ(r.timings[0].check_s, slow);
}

// summary.json records what was used: for a parameter left "not set", the
// value the stage chose (here the scene's workspace and grid); what else the
// stage reports it used; and the libraries the loaded code was built with.
TEST_F(PipelineRunner, SummaryRecordsTheValueUsedForAParameterLeftNotSet) {
  const fs::path out = dir_ / "out";
  const std::string scene = std::string(TOUCHCLOUD_SOURCE_DIR) + "/sample_clouds/fox_mask/scene.yaml";
  run("stages:\n  - id: plan\n    plugin: next_touch\n    params: {scene: " + scene + ", workspace_y_mm: [0, 12]}\n",
      1, out);
  const auto j = nlohmann::json::parse(touchcloud::test::read_file(out / "summary.json"));
  const auto& params = j["stages"][0]["params"];
  EXPECT_EQ(params["grid"], nlohmann::json::array({14, 14}));
  EXPECT_EQ(params["workspace_x_mm"], nlohmann::json::array({-60.0, 60.0}));
  EXPECT_EQ(params["workspace_y_mm"], nlohmann::json::array({0.0, 12.0}));
  EXPECT_TRUE(j["versions"].contains("eigen")) << "recorded by the sensing library, not the runtime";
}

// A stage's progress within one call (a trainer's epochs) reaches whoever
// runs it; an impossible count is a bug in the stage, reported as such.
TEST(RunContextProgress, ReachesTheRunnersCallbackAndRefusesImpossibleCounts) {
  RunRecord record;
  std::vector<std::string> seen;
  RunSettings settings;
  settings.on_progress = [&](const std::string& stage, std::int64_t done, std::int64_t total, const std::string& unit) {
    seen.push_back(stage + " " + std::to_string(done) + "/" + std::to_string(total) + " " + unit);
  };
  const RunContext ctx("train", 0, record, settings);
  ctx.progress(0, 3, "epochs");
  ctx.progress(3, 3, "epochs");
  EXPECT_EQ(seen, (std::vector<std::string>{"train 0/3 epochs", "train 3/3 epochs"}));
  for (const auto& [done, total, unit] : std::vector<std::tuple<std::int64_t, std::int64_t, std::string>>{
           {4, 3, "epochs"}, {-1, 3, "epochs"}, {0, 0, "epochs"}, {1, 3, ""}}) {
    try {
      ctx.progress(done, total, unit);
      ADD_FAILURE() << done << "/" << total << " '" << unit << "' was taken";
    } catch (const RunError& e) {
      EXPECT_NE(std::string(e.what()).find("stage 'train' reported progress " + std::to_string(done) + "/" +
                                           std::to_string(total)),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(seen.size(), 2u);
  // Nobody listening (a sweep's runs, the Python module): nothing happens.
  RunContext("quiet", 0, record).progress(1, 2, "epochs");
}
