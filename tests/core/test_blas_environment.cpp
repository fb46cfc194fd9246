// OpenBLAS's kernels as the CLI sets them up: the user's OPENBLAS_CORETYPE
// is kept; without one, the kernel touchcloud prefers for this CPU is the one
// the GP plugin's OpenBLAS runs (recorded in summary.json), and the choice is
// in the versions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "touchcloud/blas_environment.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

// Two touches of the main job: enough to load and use OpenBLAS.
nlohmann::json short_main_job(const fs::path& out, const std::string& env) {
  const auto r = test::run_cli({"run", (test::source_dir() / "pipelines/fox_mask_active.yaml").string(), "--seed", "1",
                                "--quiet", "--out", out.string(), "--set", "explore.max_iterations=2"},
                               env);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(test::read_file(out / "summary.json"));
}

std::string dense_algebra(const nlohmann::json& summary) {
  for (const auto& stage : summary.at("stages"))
    if (stage.at("id") == "fit") return stage.at("used").at("dense_algebra");
  return "";
}

}  // namespace

TEST(BlasEnvironment, TheUsersKernelChoiceIsKept) {
  test::TempDir dir;
  const auto summary = short_main_job(dir / "out", "OPENBLAS_CORETYPE=Haswell");
  const std::string algebra = dense_algebra(summary);
  if (algebra.find("OpenBLAS") == std::string::npos) GTEST_SKIP() << "the GP runs without OpenBLAS: " << algebra;
  EXPECT_NE(algebra.find(" Haswell "), std::string::npos) << algebra;
  EXPECT_EQ(summary.at("versions").at("openblas_coretype"), "Haswell (OPENBLAS_CORETYPE, set by the user)");
}

TEST(BlasEnvironment, OpenBlasRunsTheKernelChosenForThisCpu) {
  test::TempDir dir;
  const auto summary = short_main_job(dir / "out", "env -u OPENBLAS_CORETYPE");
  const std::string algebra = dense_algebra(summary);
  if (algebra.find("OpenBLAS") == std::string::npos) GTEST_SKIP() << "the GP runs without OpenBLAS: " << algebra;
  const std::string preferred = preferred_openblas_coretype();
  const std::string recorded = summary.at("versions").at("openblas_coretype");
  if (preferred.empty()) {
    EXPECT_EQ(recorded, "OpenBLAS's own detection");
  } else {
    EXPECT_NE(algebra.find(" " + preferred + " "), std::string::npos) << algebra;
    EXPECT_EQ(recorded, preferred + " (set by touchcloud from the CPU's instruction sets)");
  }
}
