// A sparse VFE GP (gp/sparse_vfe.hpp) as the toolkit's SurfaceModel: an
// immutable snapshot, like GpSurfaceModel.
#pragma once

#include <memory>

#include "gp/sparse_vfe.hpp"
#include "touchcloud/types/surface_model.hpp"

namespace touchcloud::gp_surface {

class SparseSurfaceModel final : public SurfaceModel {
 public:
  explicit SparseSurfaceModel(std::shared_ptr<const gp_surface::SparseVfeGp> gp) : gp_(std::move(gp)) {}
  std::size_t training_size() const override { return static_cast<std::size_t>(gp_->size()); }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override { return gp_->mean(xy); }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override { return gp_->variance(xy); }
  std::map<std::string, double> hyperparameters() const override;

 private:
  std::shared_ptr<const gp_surface::SparseVfeGp> gp_;
};

}  // namespace touchcloud::gp_surface
