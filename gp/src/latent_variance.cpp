#include "latent_variance.hpp"

#include <cmath>
#include <sstream>

#include "touchcloud/error.hpp"

namespace touchcloud::gp {

std::size_t clamp_latent_variance(Eigen::Ref<Eigen::VectorXd> variance_mm2, const std::string& model,
                                  Eigen::Index training_points) {
  std::size_t clamped = 0;
  for (Eigen::Index i = 0; i < variance_mm2.size(); ++i) {
    double& v = variance_mm2[i];
    if (!std::isfinite(v)) {
      std::ostringstream msg;
      msg << model << " variance: " << v << " mm^2 at query point " << i << " is not finite (the model of "
          << training_points << (training_points == 1 ? " point" : " points")
          << " has a corrupt factor, or its covariance overflows)";
      throw RunError(msg.str());
    }
    if (v < 0.0) {  // rounding: k(x,x) and the explained part nearly cancel
      v = 0.0;
      ++clamped;
    }
  }
  return clamped;
}

std::size_t clamp_latent_covariance(Eigen::Ref<Eigen::MatrixXd> covariance_mm2, const std::string& model,
                                    Eigen::Index training_points) {
  Eigen::Ref<Eigen::MatrixXd> c = covariance_mm2;
  for (Eigen::Index j = 0; j < c.cols(); ++j)
    for (Eigen::Index i = j + 1; i < c.rows(); ++i) {
      if (!std::isfinite(c(i, j))) {
        std::ostringstream msg;
        msg << model << " covariance: " << c(i, j) << " mm^2 between query points " << i << " and " << j
            << " is not finite (the model of " << training_points
            << (training_points == 1 ? " point" : " points") << " has a corrupt factor, or its covariance overflows)";
        throw RunError(msg.str());
      }
      c(j, i) = c(i, j);
    }
  Eigen::VectorXd diagonal = c.diagonal();
  const std::size_t clamped = clamp_latent_variance(diagonal, model, training_points);
  c.diagonal() = diagonal;
  return clamped;
}

}  // namespace touchcloud::gp
