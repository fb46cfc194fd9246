// Metrics and artifacts are declared beside ports: a stage reports only what
// it declares, and summary.json and the plugin's schema carry the
// declarations (unit, doc, direction, role), which consumers read.
#include <nlohmann/json.hpp>

#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/plugin_json.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

const std::string kPipeline =
    "pipeline: declared\n"
    "stages:\n  - id: l\n    loop:\n      max_iterations: 3\n      stages:\n"
    "        - id: s\n          plugin: test_declared_outputs\n";

std::string misreport_error(const std::string& what) {
  test::TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  test::StageHarness h("test_declared_outputs", {{"misreport", what}}, "s", settings);
  h.configure();
  try {
    h.process({}, {"value"});
  } catch (const RunError& e) {
    return e.what();
  }
  return "(no RunError)";
}

}  // namespace

TEST(DeclaredOutputs, AnUndeclaredMetricIsAnError) {
  EXPECT_NE(misreport_error("undeclared_metric").find("reported metric 'surprise', which it never declared"),
            std::string::npos)
      << misreport_error("undeclared_metric");
}

TEST(DeclaredOutputs, AMetricInAnotherUnitThanDeclaredIsAnError) {
  EXPECT_NE(misreport_error("wrong_unit").find("reported metric 'error_mm' in 'px', but declared it in 'mm'"),
            std::string::npos);
}

TEST(DeclaredOutputs, AnUndeclaredArtifactRoleIsAnError) {
  EXPECT_NE(misreport_error("undeclared_role").find("artifact of role 'image', which it never declared"),
            std::string::npos);
}

TEST(DeclaredOutputs, AnArtifactNamesAFileTheStageWrote) {
  EXPECT_NE(misreport_error("unwritten_file").find("'never_written.txt' as an artifact, but wrote no such file"),
            std::string::npos);
}

TEST(DeclaredOutputs, TheSchemaCarriesMetricsArtifactsAndTheCategory) {
  auto registry = test::test_registry();
  const LoadedPlugin& p = registry.load("test_declared_outputs");
  EXPECT_EQ(p.category(), PluginCategory::scoring);
  const nlohmann::json j = plugin_json(p);
  EXPECT_EQ(j["category"], "scoring");
  ASSERT_EQ(j["metrics"].size(), 2u);
  EXPECT_EQ(j["metrics"][0]["name"], "error_mm");
  EXPECT_EQ(j["metrics"][0]["unit"], "mm");
  EXPECT_EQ(j["metrics"][0]["when"], "per_item");
  EXPECT_EQ(j["metrics"][0]["direction"], "lower_is_better");
  EXPECT_EQ(j["metrics"][0]["role"], "accuracy");
  EXPECT_EQ(j["metrics"][1]["when"], "final");
  EXPECT_EQ(j["metrics"][1]["direction"], "none");
  ASSERT_EQ(j["artifacts"].size(), 1u);
  EXPECT_EQ(j["artifacts"][0]["role"], "table");
}

class DeclaredOutputsRun : public test::PipelineFixture {};

TEST_F(DeclaredOutputsRun, SummaryRecordsTheDeclarationsAndTheArtifacts) {
  Pipeline p = load(kPipeline);
  RunOptions o;
  o.out_dir = dir_.path() / "out";
  o.quiet = true;
  const auto j = nlohmann::json::parse(run_pipeline(p, o).summary_json);
  const auto& error = j["metrics"]["s.error_mm"];
  EXPECT_EQ(error["unit"], "mm");
  EXPECT_EQ(error["doc"], "a made-up error, lower is better");
  EXPECT_EQ(error["when"], "per_item");
  EXPECT_EQ(error["direction"], "lower_is_better");
  EXPECT_EQ(error["role"], "accuracy");
  EXPECT_EQ(error["series"].size(), 3u);
  EXPECT_EQ(j["metrics"]["s.calls"]["when"], "final");
  EXPECT_FALSE(j["metrics"]["s.calls"].contains("role"));
  ASSERT_EQ(j["artifacts"].size(), 1u);
  EXPECT_EQ(j["artifacts"][0]["stage"], "s");
  EXPECT_EQ(j["artifacts"][0]["role"], "table");
  EXPECT_EQ(j["artifacts"][0]["file"], "points.txt");
  EXPECT_EQ(j["artifacts"][0]["attributes"]["calls"], 3);
  EXPECT_TRUE(fs::exists(o.out_dir / "points.txt"));
}
