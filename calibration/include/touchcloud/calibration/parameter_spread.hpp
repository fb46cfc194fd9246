// How well least-squares data determine the parameters, at the solution:
// the condition number of the Jacobian with unit-length columns, and the
// parameters' covariance by the cluster sandwich
//   (J^T J)^-1 (sum over clusters c of g_c g_c^T) (J^T J)^-1,  g_c = J_c^T r_c,
// times C / (C - 1) for C clusters. Residuals within a cluster may be
// correlated (all distances of one press share its corners' pixel noise);
// clusters are taken as independent. Plain sigma^2 (J^T J)^-1 would count
// each of a press's ~1000 distances as independent and claim a spread
// several times too small.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace touchcloud::calibration {

struct ParameterSpread {
  double condition_number = 0;  // infinite when a column is zero or the columns are dependent
  Eigen::VectorXd variance;     // per parameter; empty unless condition_number is finite
};

// `cluster_rows`: consecutive row counts of the clusters, summing to j.rows().
ParameterSpread parameter_spread(const Eigen::MatrixXd& j, const Eigen::VectorXd& residuals,
                                 const std::vector<int>& cluster_rows);

}  // namespace touchcloud::calibration
