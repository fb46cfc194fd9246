#include "touchcloud/gp/surface_fit_options.hpp"

#include <array>
#include <cmath>

#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/number_text.hpp"

namespace touchcloud::gp {

namespace {

using Problem = SurfaceFitOptions::Problem;

std::string with_unit(const std::string& rule, const char* unit) {
  return *unit ? rule + " (" + unit + ")" : rule;
}
// `value` finite and >= `low` (or > `low` when `strictly`).
std::optional<Problem> bounded_below(const char* field, double value, double low, bool strictly, const char* unit = "") {
  if (std::isfinite(value) && (strictly ? value > low : value >= low)) return std::nullopt;
  return Problem{field, "value " + number_text(value) + " is out of range: must be " +
                            with_unit((strictly ? "> " : ">= ") + number_text(low), unit)};
}

}  // namespace

std::optional<Problem> SurfaceFitOptions::problem() const {
  if (kernel != KernelKind::rbf && kernel != KernelKind::matern52)
    return Problem{"kernel", "value " + std::to_string(static_cast<int>(kernel)) + " is not a kernel: must be rbf or matern52"};
  if (method != FitMethod::exact && method != FitMethod::sparse)
    return Problem{"method", "value " + std::to_string(static_cast<int>(method)) + " is not a method: must be exact or sparse"};
  const std::array<std::optional<Problem>, 8> ranges{
      bounded_below("inducing_points", inducing_points, 1, false, "points"),
      bounded_below("selection_points", selection_points, 0, false, "points"),
      bounded_below("selection_runs", selection_runs, 1, false),
      bounded_below("reselect_growth", reselect_growth, 0, false),
      bounded_below("screening_points", screening_points, 0, false),
      bounded_below("initial_lengthscale_mm", initial_lengthscale_mm, 0, true, "mm"),
      bounded_below("max_noise_mm", max_noise_mm, 0, true, "mm"),
      bounded_below("min_noise_mm", min_noise_mm, 0, false, "mm"),
  };
  for (const auto& p : ranges)
    if (p) return p;
  // The selection's noise bounds: a floor at or above the cap leaves nothing to choose from.
  if (!(min_noise_mm < max_noise_mm))
    return Problem{"min_noise_mm", "value " + number_text(min_noise_mm) + " must be below max_noise_mm (" +
                                       number_text(max_noise_mm) + " mm)"};
  if (prior_mean != PriorMean::mean && prior_mean != PriorMean::median)
    return Problem{"prior_mean", "value " + std::to_string(static_cast<int>(prior_mean)) + " is not a level: must be mean or median"};
  if (prior_mean == PriorMean::median && method != FitMethod::exact)
    return Problem{"prior_mean", "value median needs method exact (the sparse fit centres on the mean)"};
  if (max_lengthscale_mm) {
    if (auto p = bounded_below("max_lengthscale_mm", *max_lengthscale_mm, 0, true, "mm")) return p;
  }
  if (blas_threads) {
    if (auto p = bounded_below("blas_threads", *blas_threads, 1, false, "threads")) return p;
    if (!factor_algebra_threads_settable())
      return Problem{"blas_threads", "value " + std::to_string(*blas_threads) +
                                         " needs OpenBLAS, which this build is without (the thread count is OpenBLAS's)"};
  }
  return std::nullopt;
}

bool SurfaceFitOptions::is_valid(std::string* error) const {
  const auto p = problem();
  if (p && error) *error = p->text();
  return !p;
}

}  // namespace touchcloud::gp
