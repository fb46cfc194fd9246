// The surface fit's options validate themselves, as Ceres'
// Solver::Options::IsValid: the defaults pass, and each rule refuses a bad
// value with a message that names the field and the value, in problem(), in
// is_valid's text and in the InputError of a SurfaceFit given them.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "touchcloud/error.hpp"
#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/gp/surface_fit.hpp"

namespace touchcloud::gp {
namespace {

TEST(GpSurfaceFitOptions, DefaultsAreValid) {
  const SurfaceFitOptions o;
  std::string error = "unchanged";
  EXPECT_TRUE(o.is_valid(&error));
  EXPECT_EQ(error, "unchanged");
  EXPECT_TRUE(o.is_valid(nullptr));
  EXPECT_FALSE(o.problem());
}

struct BadValue {
  std::string field;
  std::string value;  // as the message shows it
  std::function<void(SurfaceFitOptions&)> set;
};

TEST(GpSurfaceFitOptions, EachRuleRefusesABadValueNamingTheFieldAndTheValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<BadValue> cases = {
      {"kernel", "7", [](SurfaceFitOptions& o) { o.kernel = static_cast<KernelKind>(7); }},
      {"method", "7", [](SurfaceFitOptions& o) { o.method = static_cast<FitMethod>(7); }},
      {"inducing_points", "0", [](SurfaceFitOptions& o) { o.inducing_points = 0; }},
      {"selection_points", "-1", [](SurfaceFitOptions& o) { o.selection_points = -1; }},
      {"selection_runs", "0", [](SurfaceFitOptions& o) { o.selection_runs = 0; }},
      {"reselect_growth", "-0.5", [](SurfaceFitOptions& o) { o.reselect_growth = -0.5; }},
      {"reselect_growth", "nan", [nan](SurfaceFitOptions& o) { o.reselect_growth = nan; }},
      {"screening_points", "-1", [](SurfaceFitOptions& o) { o.screening_points = -1; }},
      {"initial_lengthscale_mm", "0", [](SurfaceFitOptions& o) { o.initial_lengthscale_mm = 0.0; }},
      {"initial_lengthscale_mm", "inf", [inf](SurfaceFitOptions& o) { o.initial_lengthscale_mm = inf; }},
      {"max_noise_mm", "0", [](SurfaceFitOptions& o) { o.max_noise_mm = 0.0; }},
      {"max_noise_mm", "inf", [inf](SurfaceFitOptions& o) { o.max_noise_mm = inf; }},
      {"min_noise_mm", "-0.1", [](SurfaceFitOptions& o) { o.min_noise_mm = -0.1; }},
      // The rule between the two: a floor at or above the cap.
      {"min_noise_mm", "1", [](SurfaceFitOptions& o) { o.min_noise_mm = 1.0; }},
      {"min_noise_mm", "0.5", [](SurfaceFitOptions& o) { o.min_noise_mm = 0.5, o.max_noise_mm = 0.25; }},
      {"blas_threads", "0", [](SurfaceFitOptions& o) { o.blas_threads = 0; }},
      {"prior_mean", "7", [](SurfaceFitOptions& o) { o.prior_mean = static_cast<PriorMean>(7); }},
      {"prior_mean", "median", [](SurfaceFitOptions& o) { o.prior_mean = PriorMean::median, o.method = FitMethod::sparse; }},
      {"max_lengthscale_mm", "0", [](SurfaceFitOptions& o) { o.max_lengthscale_mm = 0.0; }},
      {"max_lengthscale_mm", "inf", [inf](SurfaceFitOptions& o) { o.max_lengthscale_mm = inf; }},
  };
  for (const BadValue& c : cases) {
    SCOPED_TRACE(c.field + " = " + c.value);
    SurfaceFitOptions o;
    c.set(o);
    const auto problem = o.problem();
    ASSERT_TRUE(problem) << "accepted";
    EXPECT_EQ(problem->field, c.field);
    EXPECT_NE(problem->detail.find("value " + c.value + " "), std::string::npos) << problem->detail;
    std::string error;
    EXPECT_FALSE(o.is_valid(&error));
    EXPECT_EQ(error, problem->text());
    EXPECT_EQ(error.rfind(c.field + ": ", 0), 0u) << error;
    try {
      SurfaceFit fit(o);
      ADD_FAILURE() << "a fit was made with them";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(error), std::string::npos) << e.what();
    }
  }
}

TEST(GpSurfaceFitOptions, NoiseFloorAtTheCapNamesBoth) {
  SurfaceFitOptions o;
  o.min_noise_mm = 0.25;
  o.max_noise_mm = 0.25;
  const auto problem = o.problem();
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->text(), "min_noise_mm: value 0.25 must be below max_noise_mm (0.25 mm)");
  o.min_noise_mm = 0.2;
  EXPECT_FALSE(o.problem());
}

// The thread count is OpenBLAS's: a build without it refuses the field.
TEST(GpSurfaceFitOptions, BlasThreadsNeedOpenBlas) {
  SurfaceFitOptions o;
  o.blas_threads = 2;
  const auto problem = o.problem();
  if (factor_algebra_threads_settable()) {
    EXPECT_FALSE(problem) << problem->text();
  } else {
    ASSERT_TRUE(problem);
    EXPECT_EQ(problem->field, "blas_threads");
    EXPECT_NE(problem->detail.find("OpenBLAS"), std::string::npos) << problem->detail;
  }
}

}  // namespace
}  // namespace touchcloud::gp
