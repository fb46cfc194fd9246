#include "touchcloud/calibration/parameter_spread.hpp"

#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include "touchcloud/error.hpp"

namespace touchcloud::calibration {

ParameterSpread parameter_spread(const Eigen::MatrixXd& j, const Eigen::VectorXd& residuals,
                                 const std::vector<int>& cluster_rows) {
  Eigen::Index total = 0;
  for (int n : cluster_rows) total += n;
  if (total != j.rows() || residuals.size() != j.rows())
    throw RunError("parameter_spread: clusters, Jacobian and residuals disagree in size");
  ParameterSpread spread;
  spread.condition_number = std::numeric_limits<double>::infinity();
  const Eigen::VectorXd norms = j.colwise().norm();
  if (j.cols() == 0 || !(norms.minCoeff() > 0)) return spread;
  // Unit-length columns: units (mm, rad, index) do not enter the conditioning.
  const Eigen::MatrixXd scaled = j * norms.cwiseInverse().asDiagonal();
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(scaled).singularValues();
  if (!(s(s.size() - 1) > 0)) return spread;
  spread.condition_number = s(0) / s(s.size() - 1);

  const Eigen::MatrixXd inverse_scaled = (scaled.transpose() * scaled).ldlt().solve(
      Eigen::MatrixXd::Identity(j.cols(), j.cols()));
  const Eigen::MatrixXd bread = norms.cwiseInverse().asDiagonal() * inverse_scaled * norms.cwiseInverse().asDiagonal();
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(j.cols(), j.cols());
  Eigen::Index row = 0;
  for (int n : cluster_rows) {
    const Eigen::VectorXd g = j.middleRows(row, n).transpose() * residuals.segment(row, n);
    meat += g * g.transpose();
    row += n;
  }
  const double clusters = static_cast<double>(cluster_rows.size());
  spread.variance = (clusters / std::max(1.0, clusters - 1) * bread * meat * bread).diagonal();
  return spread;
}

}  // namespace touchcloud::calibration
