#include "touchcloud/gp/training_data.hpp"

#include <algorithm>
#include <cmath>
#include <vector>
#include <sstream>

#include "touchcloud/error.hpp"

namespace touchcloud::gp {

Centring centring_of(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, PriorMean level) {
  Centring c;
  if (xy_mm.rows() == 0) return c;
  // The box middle of exactly representable coordinates is exact, so a shift
  // of the whole data set shifts the centre by exactly the same amount.
  c.x_mm = 0.5 * (xy_mm.col(0).minCoeff() + xy_mm.col(0).maxCoeff());
  c.y_mm = 0.5 * (xy_mm.col(1).minCoeff() + xy_mm.col(1).maxCoeff());
  if (level == PriorMean::mean) {
    c.z_mm = z_mm.mean();
    return c;
  }
  std::vector<double> z(z_mm.begin(), z_mm.end());
  const auto middle = z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2);
  std::nth_element(z.begin(), middle, z.end());
  c.z_mm = *middle;  // the upper median: a value of the data
  return c;
}

void check_finite(const Eigen::MatrixX2d& xy_mm, const std::string& what) {
  for (Eigen::Index i = 0; i < xy_mm.rows(); ++i) {
    if (!std::isfinite(xy_mm(i, 0)) || !std::isfinite(xy_mm(i, 1))) {
      std::ostringstream msg;
      msg << what << " " << i << " has a non-finite coordinate (x = " << xy_mm(i, 0) << " mm, y = " << xy_mm(i, 1)
          << " mm)";
      throw InputError(msg.str());
    }
  }
}

void check_training(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, const std::string& what) {
  if (xy_mm.rows() != z_mm.size()) {
    std::ostringstream msg;
    msg << what << "s: " << xy_mm.rows() << " (x, y) rows but " << z_mm.size() << " z values";
    throw InputError(msg.str());
  }
  check_finite(xy_mm, what);
  for (Eigen::Index i = 0; i < z_mm.size(); ++i) {
    if (!std::isfinite(z_mm[i])) {
      std::ostringstream msg;
      msg << what << " " << i << " has a non-finite height (z = " << z_mm[i] << " mm)";
      throw InputError(msg.str());
    }
  }
}

CentredXy centre(const Eigen::MatrixX2d& xy_mm, const Centring& c) {
  return {xy_mm.col(0).array() - c.x_mm, xy_mm.col(1).array() - c.y_mm};
}

}  // namespace touchcloud::gp
