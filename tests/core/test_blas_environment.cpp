// OpenBLAS's kernels as the CLI sets them up: the user's OPENBLAS_CORETYPE
// is kept; without one, the kernel touchcloud prefers for this CPU is the one
// the GP plugin's OpenBLAS runs (recorded in summary.json), and the choice is
// in the versions; so are the SIMD paths of the GP kernel's exponentials and
// (with the Matern kernel) of its mean's sums.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "touchcloud/blas_environment.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

// Two touches of the main job: enough to load and use OpenBLAS.
nlohmann::json short_main_job(const fs::path& out, const std::string& env, const std::string& kernel = "rbf") {
  const auto r = test::run_cli({"run", (test::source_dir() / "pipelines/fox_mask_active.yaml").string(), "--seed", "1",
                                "--quiet", "--out", out.string(), "--set", "explore.max_iterations=2", "--set",
                                "fit.kernel=" + kernel},
                               env);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(test::read_file(out / "summary.json"));
}

// The fit stage's recorded `used` value; "(absent)" where it has none.
std::string fit_used(const nlohmann::json& summary, const std::string& key) {
  for (const auto& stage : summary.at("stages"))
    if (stage.at("id") == "fit") return stage.at("used").value(key, "(absent)");
  return "";
}

std::string dense_algebra(const nlohmann::json& summary) { return fit_used(summary, "dense_algebra"); }

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

TEST(BlasEnvironment, TheKernelsSimdPathsAreRecorded) {
  test::TempDir dir;
  const auto rbf = short_main_job(dir / "rbf", "");
  const std::string exp = fit_used(rbf, "kernel_exp");
  EXPECT_TRUE(exp == "avx2+fma (SLEEF)" || exp == "sse2 (Eigen)") << exp;
  EXPECT_EQ(fit_used(rbf, "matern_mean_sums"), "(absent)") << "the RBF mean on the lattice is separable";
  const std::string sums = fit_used(short_main_job(dir / "matern", "", "matern52"), "matern_mean_sums");
  EXPECT_TRUE(sums == "avx512f (inline exp)" || sums == "avx2+fma (inline exp)" || sums == "kernel columns (Eigen)") << sums;
}
