// In-place Cholesky factorisation of a covariance matrix with a bounded jitter
// schedule: try A, then A + c I with c = first * growth^k * mean(diag A).
// Success means L L^T = A + c I with the reported c.
#pragma once

#include <functional>
#include <string>

#include <Eigen/Core>

namespace touchcloud::gp {

struct JitterSchedule {
  double first_relative = 1e-10;  // first jitter, relative to mean(diag A)
  double growth = 10.0;           // factor between tries
  int max_jitter_tries = 7;       // after the plain attempt: 1e-10 ... 1e-4 by default
  void validate() const;          // InputError naming the field
};

struct CholeskyReport {
  double jitter_mm2 = 0.0;          // c in L L^T = A + c I
  double jitter_relative = 0.0;     // c / mean(diag A)
  int attempts = 1;                 // factorisations tried, 1 = no jitter needed
};

// Writes the lower triangle of A into `storage` with `fill_lower` (called once
// per attempt, since a failed attempt overwrites it), then factorises in place:
// the lower triangle of `storage` holds L afterwards, the strict upper triangle
// is never touched. A factorisation counts as failed when Eigen's LLT reports
// it, or when a pivot L_ii^2 falls to the rounding level n * eps * mean(diag A)
// (the matrix is numerically singular and L would be noise).
// Throws RunError naming `what` after the last attempt.
CholeskyReport factor_with_jitter(Eigen::Ref<Eigen::MatrixXd> storage,
                                  const std::function<void(Eigen::Ref<Eigen::MatrixXd>)>& fill_lower,
                                  const JitterSchedule& schedule, const std::string& what);

// Whether every pivot of a computed factor lies above the rounding level.
bool pivots_above_rounding(const Eigen::Ref<const Eigen::MatrixXd>& lower, double mean_diagonal, Eigen::Index n_total);

}  // namespace touchcloud::gp
