// Kernel choice and the three hyperparameters of the surface GP z = f(x, y).
// x, y and z are in mm, so variances are in mm^2 and the lengthscale in mm.
#pragma once

#include <map>
#include <string>

#include <Eigen/Core>

namespace touchcloud::gp {

enum class KernelKind { rbf, matern52 };

std::string to_string(KernelKind kind);
KernelKind kernel_kind_from_string(const std::string& name);  // "rbf", "matern52"; InputError otherwise

struct Hyperparameters {
  double signal_variance_mm2 = 1.0;
  double lengthscale_mm = 1.0;     // isotropic in x and y
  double noise_variance_mm2 = 0.0;  // of the observed z; 0 allowed (jitter takes over)
  bool operator==(const Hyperparameters&) const = default;

  // The values under the names a SurfaceModel reports.
  std::map<std::string, double> named() const;

  // Throws InputError (naming `where`) unless the variance and lengthscale are
  // finite and > 0 and the noise is finite and >= 0.
  void validate(const std::string& where) const;
};

// The optimiser's coordinates: (log signal variance, log lengthscale, log noise).
using LogHyperparameters = Eigen::Vector3d;
LogHyperparameters to_log(const Hyperparameters& h);
Hyperparameters from_log(const LogHyperparameters& theta);

}  // namespace touchcloud::gp
