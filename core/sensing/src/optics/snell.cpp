#include "touchcloud/optics/snell.hpp"

#include <cmath>

namespace touchcloud::optics {

Refraction refract(const Eigen::Vector3d& incident, const Eigen::Vector3d& normal, double mu_from,
                   double mu_to) {
  const double c = incident.dot(normal);
  if (!(c > 0)) return {TraceStatus::MissesPlate, Eigen::Vector3d::Zero()};
  const double eta = mu_from / mu_to;
  const Eigen::Vector3d tangential = incident - c * normal;  // |tangential| = sin(theta_from)
  const double k = 1.0 - eta * eta * tangential.squaredNorm();
  if (k < 0) return {TraceStatus::TotalInternalReflection, Eigen::Vector3d::Zero()};
  // Written as tangential + normal parts: the tangential part keeps its digits
  // near normal incidence, where eta d + (sqrt(k) - eta c) n would cancel.
  return {TraceStatus::Ok, (eta * tangential + std::sqrt(k) * normal).normalized()};
}

}  // namespace touchcloud::optics
