// One scene per run: the pipeline's `scene:` reaches every stage that takes
// one, --scene replaces it everywhere, and a stage naming another object than
// the simulator is refused at load unless it says `own_scene: true`.
#include "pipeline_fixture.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;
using touchcloud::test::source_dir;

namespace {

const std::string kFox = (source_dir() / "sample_clouds" / "fox_mask" / "scene.yaml").string();
const std::string kWave = (source_dir() / "sample_clouds" / "wave_surface" / "scene.yaml").string();

// Plan, simulate and score; `top` is the pipeline's scene line, each `*_params`
// a stage's params.
std::string touch_and_score(const std::string& top, const std::string& sensor_params = "{}",
                            const std::string& score_params = "{}", const std::string& score_extra = "") {
  return "pipeline: t\n" + top +
         "stages:\n"
         "  - id: plan\n    plugin: next_touch\n"
         "  - id: sensor\n    plugin: marker_gelstereo_simulator\n    params: " + sensor_params +
         "\n    inputs: {target: plan.target}\n"
         "  - id: read\n    plugin: cloud_reader\n    params: {path: " + touchcloud::test::gel_dome_cloud() + "}\n"
         "  - id: score\n    plugin: chamfer\n" + score_extra + "    params: " + score_params +
         "\n    inputs: {cloud: read.cloud}\n";
}

std::string scene_of(const Pipeline& p, const std::string& stage) {
  return std::get<std::string>(p.parameters().at(stage).at("scene"));
}

}  // namespace

class PipelineScene : public touchcloud::test::PipelineFixture {};

TEST_F(PipelineScene, ThePipelinesSceneReachesEveryStageThatTakesOne) {
  Pipeline p = load(touch_and_score("scene: " + kFox + "\n"));
  for (const char* stage : {"plan", "sensor", "score"}) EXPECT_EQ(scene_of(p, stage), kFox) << stage;
  EXPECT_EQ(p.parameters().at("read").count("scene"), 0u);
}

TEST_F(PipelineScene, DashDashSceneReplacesItInEveryStage) {
  // The file names the fox mask at the top and again in two stages.
  const std::string yaml = touch_and_score("scene: " + kFox + "\n", "{scene: " + kFox + "}", "{scene: " + kFox + "}");
  Pipeline p = load(yaml, {{kPipelineSceneKey, kWave, "--scene"}});
  for (const char* stage : {"plan", "sensor", "score"}) EXPECT_EQ(scene_of(p, stage), kWave) << stage;
  // Without a top-level scene too.
  Pipeline q = load(touch_and_score("", "{scene: " + kFox + "}", "{scene: " + kFox + "}") +
                        "", {{kPipelineSceneKey, kWave, "--scene"}});
  for (const char* stage : {"plan", "sensor", "score"}) EXPECT_EQ(scene_of(q, stage), kWave) << stage;
}

TEST_F(PipelineScene, AStageNamingAnotherObjectThanTheSimulatorIsRefused) {
  const auto d = errors(touch_and_score("scene: " + kFox + "\n", "{}", "{scene: " + kWave + "}"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "stage 'score' (plugin chamfer) names the scene " + kWave)) << d[0].str();
  EXPECT_TRUE(mentions(d[0], "but stage 'sensor' simulates " + kFox)) << d[0].str();
  EXPECT_TRUE(mentions(d[0], "own_scene: true")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 15);  // the score stage's params
  EXPECT_GT(d[0].where.column, 1);

  // Setting only the simulator's scene leaves the planner and the score on the other object.
  const auto only_sensor = errors(touch_and_score("scene: " + kFox + "\n"), {{"sensor.scene", kWave}});
  ASSERT_EQ(only_sensor.size(), 2u);
  EXPECT_TRUE(mentions(only_sensor[0], "stage 'plan'")) << only_sensor[0].str();
  EXPECT_TRUE(mentions(only_sensor[1], "stage 'score'")) << only_sensor[1].str();
}

TEST_F(PipelineScene, OwnSceneKeepsAStagesSceneThroughDashDashScene) {
  const std::string yaml =
      touch_and_score("scene: " + kFox + "\n", "{}", "{scene: " + kWave + "}", "    own_scene: true\n");
  Pipeline p = load(yaml);
  EXPECT_EQ(scene_of(p, "score"), kWave);
  EXPECT_EQ(scene_of(p, "sensor"), kFox);
  Pipeline q = load(yaml, {{kPipelineSceneKey, kFox, "--scene"}});
  EXPECT_EQ(scene_of(q, "score"), kWave);

  const auto d = errors("pipeline: t\nstages:\n  - id: read\n    plugin: cloud_reader\n    own_scene: true\n"
                        "    params: {path: " + touchcloud::test::gel_dome_cloud() + "}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "takes no scene")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 5);
}

TEST_F(PipelineScene, ARelativeSceneIsRelativeToThePipelinesFolder) {
  const auto d = errors("pipeline: t\nscene: nowhere.yaml\nstages:\n  - id: plan\n    plugin: next_touch\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], (dir_.path() / "nowhere.yaml").string())) << d[0].str();
  EXPECT_EQ(d[0].where.line, 2);
  EXPECT_EQ(d[0].where.column, 8);
}
