// Snell's law in vector form at a flat interface.
#pragma once

#include <Eigen/Core>

#include "touchcloud/optics/trace_status.hpp"

namespace touchcloud::optics {

struct Refraction {
  TraceStatus status = TraceStatus::Ok;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // unit; zero unless status is Ok
};

// Refracts the unit direction `incident` at an interface with unit `normal`
// pointing into the second medium (incident . normal > 0), going from index
// mu_from to mu_to. Status TotalInternalReflection when no refracted ray
// exists, MissesPlate when the ray does not head into the interface.
Refraction refract(const Eigen::Vector3d& incident, const Eigen::Vector3d& normal,
                   double mu_from, double mu_to);

}  // namespace touchcloud::optics
