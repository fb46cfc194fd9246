// A fitted GP as the toolkit's SurfaceModel: an immutable snapshot, so a
// stage holding it never sees the next touch's update.
#pragma once

#include <memory>

#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/types/surface_model.hpp"

namespace touchcloud::gp {

class GpSurfaceModel final : public SurfaceModel {
 public:
  // `data_z_range_mm`: [min, max] of the training z (nothing with no data).
  GpSurfaceModel(std::shared_ptr<const gp::ExactGp> gp, std::optional<std::array<double, 2>> data_z_range_mm)
      : gp_(std::move(gp)), data_z_range_mm_(data_z_range_mm) {}
  std::size_t training_size() const override { return static_cast<std::size_t>(gp_->size()); }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override { return gp_->mean(xy); }
  Eigen::MatrixXd mean_on_lattice(const Eigen::VectorXd& xs, const Eigen::VectorXd& ys) const override {
    return gp_->mean_on_grid(xs, ys);
  }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override { return gp_->variance(xy); }
  std::optional<Eigen::MatrixXd> covariance(const Eigen::MatrixX2d& xy) const override { return gp_->covariance(xy); }
  Eigen::VectorXd candidate_mean(const Eigen::MatrixX2d& xy) const override { return gp_->candidate_mean(xy); }
  std::optional<double> noise_variance_mm2() const override { return gp_->hyperparameters().noise_variance_mm2; }
  std::optional<std::array<double, 2>> data_z_range_mm() const override { return data_z_range_mm_; }
  std::map<std::string, double> hyperparameters() const override;
  const std::shared_ptr<const gp::ExactGp>& gp() const { return gp_; }

 private:
  std::shared_ptr<const gp::ExactGp> gp_;
  std::optional<std::array<double, 2>> data_z_range_mm_;
};

}  // namespace touchcloud::gp
