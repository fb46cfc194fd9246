// Bounds for hyperparameter selection that follow the data's units: the
// lengthscale between a fraction of the typical point spacing and a multiple
// of the extent in (x, y); variances relative to the spread of z. Rescaling
// x or z (m <-> mm) rescales the bounds the same way.
#pragma once

#include <limits>
#include <optional>

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameters.hpp"

namespace touchcloud::gp {

struct DataScales {
  double spacing_mm = 0.0;      // median distance to the nearest point at a different (x, y)
  double extent_mm = 0.0;       // larger side of the (x, y) bounding box
  double z_variance_mm2 = 0.0;  // of z, floored for a constant target (see .cpp)
};
// InputError when all points share one (x, y) or a value is not finite.
DataScales data_scales(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm);

struct BoundsRules {
  double lengthscale_spacing_fraction = 0.1;  // lower lengthscale = this x spacing
  double lengthscale_extent_multiple = 10.0;  // upper lengthscale = this x extent
  double signal_variance_low = 1e-6;          // x z variance
  double signal_variance_high = 1e4;
  double noise_variance_low = 1e-8;
  double noise_variance_high = 1.0;
  // An absolute cap on the noise standard deviation, in the data's units (a
  // sensor's accuracy): without it, few or rough points can be explained as
  // all noise around a flat mean. Infinite: no cap.
  double noise_sd_max = std::numeric_limits<double>::infinity();
  // An absolute floor on it (a sensor's repeatability from touch to touch):
  // without it, a rough kernel can explain noisy touches as a noise-free
  // surface that passes through two points 0.2 mm apart and 2 mm apart in z,
  // and swings by centimetres between them. 0: no floor.
  double noise_sd_min = 0.0;
  // An absolute cap on the lengthscale, in the data's units: a long one
  // carries a steep wall's slope far past its foot, into ground no touch
  // reached. Not set: only the extent rule.
  std::optional<double> lengthscale_max_mm;
  void validate() const;  // InputError naming the field
};

struct HyperparameterBounds {
  Hyperparameters lower, upper;
  bool contains(const Hyperparameters& h) const;
};
HyperparameterBounds bounds_from_scales(const DataScales& scales, const BoundsRules& rules = {});

}  // namespace touchcloud::gp
