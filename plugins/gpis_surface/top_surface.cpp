#include "top_surface.hpp"

#include <cmath>

namespace touchcloud {

namespace {
constexpr int kBisections = 8;  // a 1 mm step to ~4 um
}  // namespace

template <class Model>
ImplicitTopSurface<Model>::ImplicitTopSurface(std::shared_ptr<const Model> model, double top_z_mm,
                                       double step_mm)
    : model_(std::move(model)), top_z_mm_(top_z_mm), step_mm_(step_mm) {}

template <class Model>
Eigen::MatrixX3d ImplicitTopSurface<Model>::surface_points(const Eigen::MatrixX2d& xy) const {
  const Eigen::Index m = xy.rows();
  const int levels = std::max(1, static_cast<int>(std::ceil(std::max(top_z_mm_, 0.0) / step_mm_))) + 1;
  // Every column at every level in one pass of the mean: level k at
  // top - k step, the last one the table.
  Eigen::MatrixX3d query(m * levels, 3);
  for (int k = 0; k < levels; ++k) {
    const double z = std::max(0.0, top_z_mm_ - k * step_mm_);
    query.middleRows(k * m, m) << xy, Eigen::VectorXd::Constant(m, z);
  }
  const Eigen::VectorXd f = model_->mean(query);
  Eigen::VectorXd above = Eigen::VectorXd::Constant(m, top_z_mm_), below = Eigen::VectorXd::Zero(m);
  std::vector<bool> crossed(static_cast<std::size_t>(m), false);
  for (Eigen::Index i = 0; i < m; ++i) {
    if (f(i) <= 0) {  // inside at the top already: the surface is at or above the box
      crossed[static_cast<std::size_t>(i)] = true;
      above(i) = below(i) = top_z_mm_;
      continue;
    }
    for (int k = 1; k < levels; ++k)
      if (f(k * m + i) <= 0) {
        crossed[static_cast<std::size_t>(i)] = true;
        above(i) = query(((k - 1) * m) + i, 2);
        below(i) = query(k * m + i, 2);
        break;
      }
  }
  for (int b = 0; b < kBisections; ++b) {
    Eigen::MatrixX3d middle(m, 3);
    middle << xy, 0.5 * (above + below);
    const Eigen::VectorXd fm = model_->mean(middle);
    for (Eigen::Index i = 0; i < m; ++i) {
      if (!crossed[static_cast<std::size_t>(i)] || above(i) == below(i)) continue;
      (fm(i) > 0 ? above(i) : below(i)) = middle(i, 2);
    }
  }
  Eigen::MatrixX3d points(m, 3);
  for (Eigen::Index i = 0; i < m; ++i)
    points.row(i) << xy(i, 0), xy(i, 1), crossed[static_cast<std::size_t>(i)] ? 0.5 * (above(i) + below(i)) : 0.0;
  return points;
}

template <class Model>
Eigen::VectorXd ImplicitTopSurface<Model>::mean(const Eigen::MatrixX2d& xy) const { return surface_points(xy).col(2); }

template <class Model>
Eigen::VectorXd ImplicitTopSurface<Model>::variance(const Eigen::MatrixX2d& xy) const {
  return model_->variance(surface_points(xy));
}

template <class Model>
std::optional<std::array<double, 2>> ImplicitTopSurface<Model>::data_z_range_mm() const {
  const Eigen::MatrixX3d& c = model_->contact_points();
  if (c.rows() == 0) return std::nullopt;
  return std::array<double, 2>{c.col(2).minCoeff(), c.col(2).maxCoeff()};
}

template <class Model>
std::map<std::string, double> ImplicitTopSurface<Model>::hyperparameters() const {
  const gp::Hyperparameters& h = model_->hyperparameters();
  return {{"scale_mm", h.lengthscale_mm}, {"signal_variance_mm2", h.signal_variance_mm2},
          {"noise_variance_mm2", h.noise_variance_mm2}};
}

template class ImplicitTopSurface<gp::ImplicitSurface>;
template class ImplicitTopSurface<gp::SparseImplicitSurface>;

}  // namespace touchcloud
