// The implicit surface as a press from above meets it: at each (x, y) the
// highest point of its zero level set below `top_z_mm`, found by stepping
// down the signed distance and bisecting the first sign change, or the table
// (z = 0, base frame) where the column never enters the object. Its variance
// there is the signed distance's (mm^2; a signed distance changes by 1 mm per
// mm across the surface, so it stands for the surface's). This is the
// surface_model the planner reads (next_touch's max_variance), so touches from
// above are chosen where the implicit surface is least certain.
#pragma once

#include <memory>

#include "touchcloud/gp/implicit_surface.hpp"
#include "touchcloud/gp/sparse_implicit_surface.hpp"
#include "touchcloud/types/surface_model.hpp"

namespace touchcloud {

// Model: gp::ImplicitSurface or gp::SparseImplicitSurface (instantiated for both).
template <class Model>
class ImplicitTopSurface final : public SurfaceModel {
 public:
  // `model` must not change while this view lives (the stage copies it
  // before the next touch if this view is still held).
  ImplicitTopSurface(std::shared_ptr<const Model> model, double top_z_mm, double step_mm);

  std::size_t training_size() const override { return static_cast<std::size_t>(model_->training_size()); }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override;
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override;
  std::optional<std::array<double, 2>> data_z_range_mm() const override;
  std::map<std::string, double> hyperparameters() const override;

 private:
  Eigen::MatrixX3d surface_points(const Eigen::MatrixX2d& xy) const;

  std::shared_ptr<const Model> model_;
  double top_z_mm_, step_mm_;
};

}  // namespace touchcloud
