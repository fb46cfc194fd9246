#include "touchcloud/gp/hyperparameter_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "touchcloud/gp/training_data.hpp"
#include "touchcloud/error.hpp"

namespace touchcloud::gp {

DataScales data_scales(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm) {
  check_training(xy_mm, z_mm, "training point");
  const Eigen::Index n = xy_mm.rows();
  if (n == 0) throw InputError("GP hyperparameter selection: no training points");
  const CentredXy p = centre(xy_mm, centring_of(xy_mm, z_mm));
  DataScales s;
  s.extent_mm = std::max(p.x.maxCoeff() - p.x.minCoeff(), p.y.maxCoeff() - p.y.minCoeff());
  if (!(s.extent_mm > 0)) {
    std::ostringstream msg;
    msg << "GP hyperparameter selection: all " << n << " training points share (x, y) = (" << xy_mm(0, 0) << ", "
        << xy_mm(0, 1) << ") mm, so there is no length scale to select";
    throw InputError(msg.str());
  }

  // Nearest neighbour at a different position, brute force: O(n^2) distance
  // evaluations are cheap next to one O(n^3) likelihood evaluation.
  std::vector<double> nearest(static_cast<std::size_t>(n));
  Eigen::ArrayXd d2(n);
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < n; ++i) {
    d2 = (p.x.array() - p.x[i]).square() + (p.y.array() - p.y[i]).square();
    d2 = (d2 > 0.0).select(d2, inf);
    nearest[static_cast<std::size_t>(i)] = d2.minCoeff();
  }
  const auto mid = nearest.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(nearest.begin(), mid, nearest.end());
  s.spacing_mm = std::sqrt(*mid);

  const Eigen::ArrayXd zc = z_mm.array() - z_mm.mean();
  s.z_variance_mm2 = zc.square().mean();
  // A flat plate has no spread in z; fall back to a tiny scale tied to the
  // heights themselves (or to the extent when they are all zero) so that the
  // bounds stay finite and still scale with the units.
  const double magnitude = z_mm.cwiseAbs().maxCoeff() > 0 ? z_mm.cwiseAbs().maxCoeff() : s.extent_mm;
  const double floor = 1e-6 * magnitude;
  s.z_variance_mm2 = std::max(s.z_variance_mm2, floor * floor);
  return s;
}

void BoundsRules::validate() const {
  auto check = [](const char* low_name, double low, const char* high_name, double high) {
    if (!(low > 0) || !(high >= low) || !std::isfinite(high)) {
      std::ostringstream msg;
      msg << "GP hyperparameter bounds: need 0 < " << low_name << " (" << low << ") <= " << high_name << " (" << high
          << ") < inf";
      throw InputError(msg.str());
    }
  };
  if (!(lengthscale_spacing_fraction > 0) || !(lengthscale_extent_multiple > 0) ||
      !std::isfinite(lengthscale_spacing_fraction) || !std::isfinite(lengthscale_extent_multiple)) {
    std::ostringstream msg;
    msg << "GP hyperparameter bounds: lengthscale_spacing_fraction (" << lengthscale_spacing_fraction
        << ") and lengthscale_extent_multiple (" << lengthscale_extent_multiple << ") must be finite and > 0";
    throw InputError(msg.str());
  }
  check("signal_variance_low", signal_variance_low, "signal_variance_high", signal_variance_high);
  check("noise_variance_low", noise_variance_low, "noise_variance_high", noise_variance_high);
  if (lengthscale_max_mm && !(*lengthscale_max_mm > 0 && std::isfinite(*lengthscale_max_mm))) {
    std::ostringstream msg;
    msg << "GP hyperparameter bounds: lengthscale_max_mm (" << *lengthscale_max_mm << ") must be finite and > 0";
    throw InputError(msg.str());
  }
  if (!(noise_sd_max > 0)) {
    std::ostringstream msg;
    msg << "GP hyperparameter bounds: noise_sd_max (" << noise_sd_max << ") must be > 0 (infinite: no cap)";
    throw InputError(msg.str());
  }
  if (!(noise_sd_min >= 0) || !(noise_sd_min < noise_sd_max)) {
    std::ostringstream msg;
    msg << "GP hyperparameter bounds: noise_sd_min (" << noise_sd_min << ") must be >= 0 (0: no floor) and below "
        << "noise_sd_max (" << noise_sd_max << ")";
    throw InputError(msg.str());
  }
}

bool HyperparameterBounds::contains(const Hyperparameters& h) const {
  return h.signal_variance_mm2 >= lower.signal_variance_mm2 && h.signal_variance_mm2 <= upper.signal_variance_mm2 &&
         h.lengthscale_mm >= lower.lengthscale_mm && h.lengthscale_mm <= upper.lengthscale_mm &&
         h.noise_variance_mm2 >= lower.noise_variance_mm2 && h.noise_variance_mm2 <= upper.noise_variance_mm2;
}

HyperparameterBounds bounds_from_scales(const DataScales& s, const BoundsRules& rules) {
  rules.validate();
  HyperparameterBounds b;
  b.lower.lengthscale_mm = rules.lengthscale_spacing_fraction * s.spacing_mm;
  b.upper.lengthscale_mm = rules.lengthscale_extent_multiple * s.extent_mm;
  if (rules.lengthscale_max_mm) b.upper.lengthscale_mm = std::min(b.upper.lengthscale_mm, *rules.lengthscale_max_mm);
  b.upper.lengthscale_mm = std::max(b.lower.lengthscale_mm, b.upper.lengthscale_mm);
  b.lower.signal_variance_mm2 = rules.signal_variance_low * s.z_variance_mm2;
  b.upper.signal_variance_mm2 = rules.signal_variance_high * s.z_variance_mm2;
  b.lower.noise_variance_mm2 =
      std::max(rules.noise_variance_low * s.z_variance_mm2, rules.noise_sd_min * rules.noise_sd_min);
  b.upper.noise_variance_mm2 = std::max(b.lower.noise_variance_mm2,
                                        std::min(rules.noise_variance_high * s.z_variance_mm2,
                                                 rules.noise_sd_max * rules.noise_sd_max));
  return b;
}

}  // namespace touchcloud::gp
