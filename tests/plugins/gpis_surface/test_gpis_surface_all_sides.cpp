// gpis_surface's thin-plate kernel on touches all round an object, in the
// shipped pipeline with its kernel set to thin_plate: the step block
// (90 x 50 x 40 mm) touched from every side by side_touch's space-filling
// start (20 touches that do not depend on the fit, so the same on every
// CPU: touches chosen by the fit's variance differ in the last bits between
// AVX2 and AVX-512 machines, and so do their paths). Within them the
// covariance with R at the touches' diameter has negative eigenvalues beyond
// the jitter schedule (the kernel is only conditionally positive definite; a
// long box's surface makes it show).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace fs = std::filesystem;
using touchcloud::test::run_cli;

// The run goes on with R's floor raised to 1.5 diameters, says so in the
// summary's notes, and still lies on the block. The note names the run's
// touch: touch 16 adds no point, so the model's 16th touch is the run's 17th.
TEST(GpisSurfaceAllSides, ThinPlateRaisesItsScaleInsteadOfFailingAndSaysSo) {
  touchcloud::test::TempDir dir;
  const auto r = run_cli({"run", (touchcloud::test::source_dir() / "pipelines/closed_object_all_sides.yaml").string(),
                          "--scene",
                          (touchcloud::test::source_dir() / "sample_clouds/closed_objects/step/scene.yaml").string(),
                          "--seed", "1", "--quiet", "--out", (dir / "out").string(), "--set",
                          "explore.max_iterations=20", "--set", "plan.start_touches=20", "--set",
                          "fit.kernel=thin_plate"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = nlohmann::json::parse(touchcloud::test::read_file(dir / "out/summary.json"));
  ASSERT_TRUE(s["notes"].contains("fit.thin_plate_scale")) << s["notes"].dump();
  EXPECT_NE(s["notes"]["fit.thin_plate_scale"].get<std::string>().find("at least 1.5 times their diameter from touch 17 on"),
            std::string::npos)
      << s["notes"].dump();
  EXPECT_EQ(s["metrics"]["sensor.touches"]["value"].get<double>(), 20);
  EXPECT_LT(s["metrics"]["score.chamfer_est_to_gt"]["value"].get<double>(), 1.5);
}
