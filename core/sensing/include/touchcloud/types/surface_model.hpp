// A fitted surface z = f(x, y) in the base frame (mm), with its uncertainty.
// Implemented by surface-fitting plugins (the Gaussian process in gp_surface).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "touchcloud/data_type_name.hpp"

namespace touchcloud {

class SurfaceModel {
 public:
  virtual ~SurfaceModel() = default;
  virtual std::size_t training_size() const = 0;
  // Posterior mean at each row (x, y) of `xy`.
  virtual Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const = 0;
  // Mean on the lattice xs x ys: result(i, j) at (xs[i], ys[j]). Models with a
  // faster path than mean() at every point (a separable kernel) override it.
  virtual Eigen::MatrixXd mean_on_lattice(const Eigen::VectorXd& xs, const Eigen::VectorXd& ys) const {
    const Eigen::VectorXd z = mean(lattice_points(xs, ys));
    return Eigen::Map<const Eigen::MatrixXd>(z.data(), xs.size(), ys.size());
  }
  // Posterior variance (mm^2) at each row; finite and >= 0.
  virtual Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const = 0;
  // Posterior covariance (mm^2) of the latent surface among the rows of `xy`:
  // symmetric m x m, its diagonal variance(xy), every entry finite. What a
  // touch there would take away from the uncertainty elsewhere needs it
  // (next_touch's footprint_variance_reduction). Nothing for a model that
  // cannot give it.
  virtual std::optional<Eigen::MatrixXd> covariance(const Eigen::MatrixX2d& /*xy*/) const { return std::nullopt; }
  // Variance (mm^2) of the noise on one observed z; nothing when the model
  // does not say.
  virtual std::optional<double> noise_variance_mm2() const { return std::nullopt; }
  // Variance on the lattice, laid out as mean_on_lattice's result.
  Eigen::MatrixXd variance_on_lattice(const Eigen::VectorXd& xs, const Eigen::VectorXd& ys) const {
    const Eigen::VectorXd v = variance(lattice_points(xs, ys));
    return Eigen::Map<const Eigen::MatrixXd>(v.data(), xs.size(), ys.size());
  }
  // The lattice xs x ys as rows (x, y), x fastest.
  static Eigen::MatrixX2d lattice_points(const Eigen::VectorXd& xs, const Eigen::VectorXd& ys) {
    Eigen::MatrixX2d xy(xs.size() * ys.size(), 2);
    for (Eigen::Index j = 0; j < ys.size(); ++j)
      for (Eigen::Index i = 0; i < xs.size(); ++i) xy.row(j * xs.size() + i) << xs[i], ys[j];
    return xy;
  }
  // [min, max] z (mm) of the data the model was fitted to; nothing when it
  // has none or does not say. A mean far outside it is extrapolation: stages
  // that sample the surface mask it or refuse it rather than pass it on.
  virtual std::optional<std::array<double, 2>> data_z_range_mm() const { return std::nullopt; }
  // Named hyperparameters with units in the name ("lengthscale_mm").
  virtual std::map<std::string, double> hyperparameters() const = 0;
  // Posterior mean at the rows of `xy` by way of what covariance(xy) keeps: a
  // model that caches the cross-covariances of a query set asked for again
  // (next_touch's grid, every touch) answers from them without a pass over
  // all its data. Equal to mean(xy) up to rounding, not bit for bit; by
  // default mean(xy). (Plugin ABI 6.)
  virtual Eigen::VectorXd candidate_mean(const Eigen::MatrixX2d& xy) const { return mean(xy); }
};
// A model does not change once a stage has output it, so a stage that gets
// the same pointer again may reuse what it computed from it.
using SurfaceModelPtr = std::shared_ptr<const SurfaceModel>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::SurfaceModelPtr, "surface_model");
