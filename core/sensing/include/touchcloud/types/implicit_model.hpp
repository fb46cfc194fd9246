// A closed surface's model as a planner reads it: the signed distance (mm,
// < 0 inside, 0 on the surface, > 0 outside) and its variance (mm^2) at
// points of the base frame. Implemented by gpis_surface; a model does not
// change once a stage has output it.
#pragma once

#include <memory>

#include <Eigen/Core>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

class ImplicitModel {
 public:
  virtual ~ImplicitModel() = default;
  virtual Eigen::VectorXd mean(const Eigen::MatrixX3d& points_mm) const = 0;
  // Finite and >= 0.
  virtual Eigen::VectorXd variance(const Eigen::MatrixX3d& points_mm) const = 0;
};
using ImplicitModelPtr = std::shared_ptr<const ImplicitModel>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::ImplicitModelPtr, "implicit_model");
