// Every way a pipeline file can be wrong is reported with FILE:LINE:COL,
// before anything runs.
#include "pipeline_fixture.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

namespace {

std::string read_thin_write(const std::string& thin_params, const std::string& thin_inputs = "{cloud: read.cloud}") {
  return "pipeline: t\nstages:\n"
         "  - id: read\n    plugin: cloud_reader\n    params: {path: " + touchcloud::test::gel_dome_cloud() + "}\n"
         "  - id: thin\n    plugin: downsample\n    params: " + thin_params + "\n    inputs: " + thin_inputs + "\n";
}
}  // namespace

class PipelineValidation : public touchcloud::test::PipelineFixture {};

TEST_F(PipelineValidation, AValidPipelineLoadsWithResolvedParameters) {
  Pipeline p = load(read_thin_write("{method: random, keep_ratio: 0.5}"));
  EXPECT_EQ(p.name(), "t");
  const auto params = p.parameters();
  EXPECT_EQ(std::get<std::string>(params.at("thin").at("method")), "random");
  EXPECT_EQ(std::get<double>(params.at("thin").at("keep_ratio")), 0.5);
  EXPECT_EQ(std::get<double>(params.at("thin").at("leaf_size_mm")), 1.0) << "defaults are resolved too";
}

TEST_F(PipelineValidation, MalformedYamlGivesItsPosition) {
  const auto d = errors("pipeline: t\nstages:\n  - id: a\n    params: {x: [1, 2}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "malformed YAML")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 4);
  EXPECT_GT(d[0].where.column, 1);
  EXPECT_EQ(d[0].str().rfind((dir_ / "p.yaml").string() + ":4:", 0), 0u) << d[0].str();
}

TEST_F(PipelineValidation, UnknownPluginSuggestsTheNearestName) {
  const auto d = errors("stages:\n  - id: a\n    plugin: downsampel\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "unknown plugin 'downsampel'; did you mean 'downsample'?")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 3);
  EXPECT_EQ(d[0].where.column, 13);
}

TEST_F(PipelineValidation, UnknownParameterIsAnErrorNotIgnored) {
  const auto d = errors(read_thin_write("{method: voxel, leaf_size: 2}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "has no parameter 'leaf_size'; did you mean 'leaf_size_mm'?")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 8);
}

TEST_F(PipelineValidation, WrongTypeSaysWhatWasExpected) {
  const auto d = errors(read_thin_write("{leaf_size_mm: fine}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "parameter 'leaf_size_mm': expected a number, got 'fine'")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 8);
  EXPECT_EQ(d[0].where.column, 28);
}

TEST_F(PipelineValidation, OutOfRangeStatesTheRuleAndUnit) {
  const auto d = errors(read_thin_write("{leaf_size_mm: -2}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "value -2 is out of range: must be > 0 (mm)")) << d[0].str();
  const auto d2 = errors(read_thin_write("{method: octree}"));
  ASSERT_EQ(d2.size(), 1u);
  EXPECT_TRUE(mentions(d2[0], "must be one of: voxel, random")) << d2[0].str();
}

TEST_F(PipelineValidation, MissingInputNamesThePortAndItsType) {
  const auto d = errors("stages:\n  - id: thin\n    plugin: downsample\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "missing its input 'cloud' (point_cloud)")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 2);
}

TEST_F(PipelineValidation, UnknownInputsStagesAndOutputs) {
  auto d = errors(read_thin_write("{}", "{cloud: raed.cloud}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "reads from unknown stage 'raed'; did you mean 'read'?")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 9);

  d = errors(read_thin_write("{}", "{cloud: read.points}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "has no output 'points'")) << d[0].str();

  d = errors(read_thin_write("{}", "{cloud: read.cloud, clouds: read.cloud}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "has no input 'clouds'; did you mean 'cloud'?")) << d[0].str();

  d = errors(read_thin_write("{}", "{cloud: readcloud}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "is not an output reference")) << d[0].str();
}

TEST_F(PipelineValidation, MismatchedTypesAreRefused) {
  const auto d = errors(
      "stages:\n  - id: c\n    plugin: test_counter\n"
      "  - id: thin\n    plugin: downsample\n    inputs: {cloud: c.done}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "takes point_cloud but c.done gives bool")) << d[0].str();
}

TEST_F(PipelineValidation, CyclesAreReportedWithTheirPath) {
  const auto d = errors(
      "stages:\n"
      "  - id: a\n    plugin: test_counter\n    inputs: {previous: b.value}\n"
      "  - id: b\n    plugin: test_counter\n    inputs: {previous: a.value}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "cycle: a -> b -> a")) << d[0].str();
}

TEST_F(PipelineValidation, DuplicateIdsPointAtBothPlaces) {
  const auto d = errors(
      "stages:\n  - id: a\n    plugin: test_counter\n  - id: a\n    plugin: test_counter\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "duplicate stage id 'a' (first defined at ")) << d[0].str();
  EXPECT_TRUE(mentions(d[0], ":2:")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 4);
}

TEST_F(PipelineValidation, MissingOrFolderInputFiles) {
  auto d = errors("stages:\n  - id: r\n    plugin: cloud_reader\n    params: {path: nowhere.pcd}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "input file " + (dir_ / "nowhere.pcd").string() + " does not exist")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 4);
  EXPECT_EQ(d[0].where.column, 20);

  std::filesystem::create_directories(dir_ / "folder.pcd");
  d = errors("stages:\n  - id: r\n    plugin: cloud_reader\n    params: {path: folder.pcd}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "is a folder, not a file")) << d[0].str();

  d = errors("stages:\n  - id: r\n    plugin: cloud_reader\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "parameter 'path' names an input file and must be set")) << d[0].str();
}

TEST_F(PipelineValidation, AllProblemsAreReportedInOnePass) {
  const auto d = errors(
      "stages:\n"
      "  - id: a\n    plugin: downsample\n    params: {leaf_size_mm: 0, methd: voxel}\n    inputs: {cloud: x.cloud}\n"
      "  - id: b\n    plugin: no_such_plugin\n");
  EXPECT_GE(d.size(), 3u);
}

TEST_F(PipelineValidation, StructureErrors) {
  EXPECT_TRUE(mentions(errors("stages: 3\n").at(0), "'stages' is a list"));
  EXPECT_TRUE(mentions(errors("pipeline: x\n").at(0), "has no 'stages'"));
  EXPECT_TRUE(mentions(errors("stages:\n  - plugin: downsample\n").at(0), "has no 'id'"));
  EXPECT_TRUE(mentions(errors("stages:\n  - id: 1a\n    plugin: downsample\n").at(0), "not an identifier"));
  EXPECT_TRUE(mentions(errors("stages:\n  - id: a\n    plugn: downsample\n").at(0),
                       "unknown key 'plugn' in stage 'a'; did you mean 'plugin'?"));
  EXPECT_TRUE(mentions(errors("").at(0), "empty"));
}

TEST_F(PipelineValidation, LoopRules) {
  const std::string body = "      stages:\n        - id: c\n          plugin: test_counter\n";
  EXPECT_TRUE(mentions(errors("stages:\n  - id: l\n    loop:\n      max_iterations: 0\n" + body).at(0),
                       "'max_iterations' must be >= 1"));
  EXPECT_TRUE(mentions(errors("stages:\n  - id: l\n    loop:\n" + body).at(0), "has no 'max_iterations'"));
  EXPECT_TRUE(mentions(errors("stages:\n  - id: l\n    loop:\n      max_iterations: 3\n      until: c.value\n" + body).at(0),
                       "gives number, not bool"));
  // @previous needs a shared loop, and an optional input.
  EXPECT_TRUE(mentions(errors("stages:\n  - id: a\n    plugin: test_counter\n"
                              "  - id: b\n    plugin: test_counter\n    inputs: {previous: a.value@previous}\n").at(0),
                       "'@previous' needs a and this stage inside one loop"));
  EXPECT_TRUE(mentions(errors("stages:\n  - id: r\n    plugin: cloud_reader\n    params: {path: " + touchcloud::test::gel_dome_cloud() + "}\n"
                              "  - id: l\n    loop:\n      max_iterations: 2\n      stages:\n"
                              "        - id: t\n          plugin: downsample\n          inputs: {cloud: t.cloud@previous}\n").at(0),
                       "fed from the previous iteration"));
}

// A relative path in the pipeline is taken from the pipeline file's folder,
// one given with --set from the current directory: a missing file's message
// names the absolute path tried and which rule made it.
TEST_F(PipelineValidation, AMissingRelativeFileNamesTheAbsolutePathTriedAndWhy) {
  std::filesystem::create_directories(dir_ / "pipelines");
  write("stages:\n  - id: r\n    plugin: cloud_reader\n    params: {path: ../data/a.pcd}\n", "pipelines/p.yaml");
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir_.path());
  std::vector<Diagnostic> in_file, on_command_line;
  try {
    Pipeline::load("pipelines/p.yaml", {}, registry_);
  } catch (const InputError& e) {
    in_file = e.diagnostics();
  }
  try {
    Pipeline::load("pipelines/p.yaml", {{"r.path", "b.pcd"}}, registry_);
  } catch (const InputError& e) {
    on_command_line = e.diagnostics();
  }
  std::filesystem::current_path(cwd);
  const std::string root = std::filesystem::canonical(dir_.path()).string();
  ASSERT_EQ(in_file.size(), 1u);
  EXPECT_TRUE(mentions(in_file[0], "input file " + root + "/data/a.pcd does not exist")) << in_file[0].str();
  EXPECT_TRUE(mentions(in_file[0], "relative to its file's folder, " + root + "/pipelines)")) << in_file[0].str();
  ASSERT_EQ(on_command_line.size(), 1u);
  EXPECT_TRUE(mentions(on_command_line[0], "input file " + root + "/b.pcd does not exist")) << on_command_line[0].str();
  EXPECT_TRUE(mentions(on_command_line[0], "--set paths are relative to the current directory"))
      << on_command_line[0].str();
}

TEST_F(PipelineValidation, OverridesAreCheckedLikeTheFile) {
  const std::string yaml = read_thin_write("{}");
  Pipeline p = load(yaml, {{"thin.leaf_size_mm", "3.5"}, {"thin.method", "random"}});
  EXPECT_EQ(std::get<double>(p.parameters().at("thin").at("leaf_size_mm")), 3.5);

  auto d = errors(yaml, {{"thin.leaf_size_mm", "big"}});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].where.file, "--set thin.leaf_size_mm=big");
  EXPECT_TRUE(mentions(d[0], "expected a number, got 'big'")) << d[0].str();
  EXPECT_TRUE(mentions(errors(yaml, {{"thn.leaf_size_mm", "2"}}).at(0), "no stage with id 'thn'; did you mean 'thin'?"));
  EXPECT_TRUE(mentions(errors(yaml, {{"thin.leaf", "2"}}).at(0), "did you mean 'leaf_size_mm'?"));
  EXPECT_THROW(parse_override("thin.leaf_size_mm"), InputError);
}
