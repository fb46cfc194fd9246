// The last step of a latent variance, prior minus what the data explain, for
// every model here: rounding may leave a value a little below 0 (clamped and
// counted), but a non-finite value means a corrupt factor or an overflow, and
// must never reach the next-touch choice as a number (stability case 8).
#pragma once

#include <cstddef>
#include <string>

#include <Eigen/Core>

namespace touchcloud::gp {

// Clamps negative values at 0 and returns how many. RunError naming `model`,
// the query point and its value at the first value that is not finite (NaN
// or +-inf; -inf must not pass as a clamped 0).
std::size_t clamp_latent_variance(Eigen::Ref<Eigen::VectorXd> variance_mm2, const std::string& model,
                                  Eigen::Index training_points);

// The same for a posterior covariance matrix: its diagonal is clamped as
// above, and every entry must be finite (RunError naming the first that is
// not). The lower triangle is copied to the upper, so the result is exactly
// symmetric whatever rounding left.
std::size_t clamp_latent_covariance(Eigen::Ref<Eigen::MatrixXd> covariance_mm2, const std::string& model,
                                    Eigen::Index training_points);

}  // namespace touchcloud::gp
