#include "touchcloud/gp/jittered_cholesky.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "touchcloud/gp/factor_algebra.hpp"

#include "touchcloud/error.hpp"

namespace touchcloud::gp {

void JitterSchedule::validate() const {
  auto fail = [](const std::string& field, double value, const char* rule) {
    std::ostringstream msg;
    msg << "jitter schedule: " << field << " = " << value << " must be " << rule;
    throw InputError(msg.str());
  };
  if (!(first_relative > 0) || !std::isfinite(first_relative)) fail("first_relative", first_relative, "finite and > 0");
  if (!(growth > 1) || !std::isfinite(growth)) fail("growth", growth, "finite and > 1");
  if (max_jitter_tries < 0 || max_jitter_tries > 30) fail("max_jitter_tries", max_jitter_tries, "in [0, 30]");
}

bool pivots_above_rounding(const Eigen::Ref<const Eigen::MatrixXd>& lower, double mean_diagonal, Eigen::Index n_total) {
  const double floor = static_cast<double>(n_total) * std::numeric_limits<double>::epsilon() * mean_diagonal;
  return (lower.diagonal().array().square() > floor).all();
}

CholeskyReport factor_with_jitter(Eigen::Ref<Eigen::MatrixXd> storage,
                                  const std::function<void(Eigen::Ref<Eigen::MatrixXd>)>& fill_lower,
                                  const JitterSchedule& schedule, const std::string& what) {
  schedule.validate();
  const Eigen::Index n = storage.rows();
  CholeskyReport report;
  if (n == 0) return report;

  double mean_diagonal = 0.0;
  for (int attempt = 0; attempt <= schedule.max_jitter_tries; ++attempt) {
    fill_lower(storage);
    if (attempt == 0) {
      mean_diagonal = storage.diagonal().mean();
      if (!std::isfinite(mean_diagonal) || mean_diagonal <= 0) {
        std::ostringstream msg;
        msg << what << ": covariance diagonal has mean " << mean_diagonal << ", not a finite positive value";
        throw RunError(msg.str());
      }
    }
    const double relative = attempt == 0 ? 0.0 : schedule.first_relative * std::pow(schedule.growth, attempt - 1);
    const double jitter = relative * mean_diagonal;
    storage.diagonal().array() += jitter;
    if (cholesky_lower_in_place(storage) && pivots_above_rounding(storage, mean_diagonal, n)) {
      report.jitter_mm2 = jitter;
      report.jitter_relative = relative;
      report.attempts = attempt + 1;
      return report;
    }
  }
  std::ostringstream msg;
  const double last = schedule.max_jitter_tries == 0
                          ? 0.0
                          : schedule.first_relative * std::pow(schedule.growth, schedule.max_jitter_tries - 1);
  msg << what << ": Cholesky factorisation of the " << n << " x " << n
      << " covariance failed after " << schedule.max_jitter_tries + 1 << " attempts (last jitter " << last
      << " x mean diagonal " << mean_diagonal << "); the matrix is not positive definite";
  throw RunError(msg.str());
}

}  // namespace touchcloud::gp
