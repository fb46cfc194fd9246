// An implicit surface (ImplicitSurface, SparseImplicitSurface) as a planner
// reads it (touchcloud/types/implicit_model.hpp): held, not copied, so the
// model must not change while this is out; gpis_surface copies its model
// before the next touch while another stage still holds it.
#pragma once

#include <memory>

#include "touchcloud/types/implicit_model.hpp"

namespace touchcloud::gp {

template <class Model>
class HeldImplicitModel final : public ImplicitModel {
 public:
  explicit HeldImplicitModel(std::shared_ptr<const Model> model) : model_(std::move(model)) {}
  Eigen::VectorXd mean(const Eigen::MatrixX3d& points_mm) const override { return model_->mean(points_mm); }
  Eigen::VectorXd variance(const Eigen::MatrixX3d& points_mm) const override { return model_->variance(points_mm); }

 private:
  std::shared_ptr<const Model> model_;
};

}  // namespace touchcloud::gp
