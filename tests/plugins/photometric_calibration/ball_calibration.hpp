// A photometric calibration made the way pipelines/calibrate_gelsight.yaml
// makes it: presses of the shipped calibration ball, each fed to the
// photometric_calibration stage, which writes its file at finish.
#pragma once

#include <vector>

#include "gelsight_fixture.hpp"
#include "stage_harness.hpp"

namespace touchcloud::test {

inline constexpr double kBallPressMm = 0.7;  // travel past first contact of each press

inline std::filesystem::path calibrate_on_ball(const TempDir& dir, const std::vector<Eigen::Vector2d>& targets,
                                               int degree = 3) {
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  StageHarness stage("photometric_calibration",
                     {{"sensor", (source_dir() / "sample_clouds/gelsight_ball/scene.yaml").string()},
                      {"path", std::string("calibration.yaml")},
                      {"degree", std::int64_t{degree}}},
                     "calibrate", settings);
  stage.configure();
  simulation::GelSightSimulation sim(ball_scene(), 1);
  for (const auto& xy : targets) {
    press_pad_into(sim, xy, kBallPressMm);
    stage.process({{"image", MonoColourFramePtr(std::make_shared<MonoColourFrame>(sim.render()))},
                   {"reference", MonoColourFramePtr(std::make_shared<MonoColourFrame>(sim.render_reference()))}},
                  {});
    sim.step(xy, true);  // the recorded frame ends the touch
  }
  stage.finish();
  return dir / "calibration.yaml";
}

}  // namespace touchcloud::test
