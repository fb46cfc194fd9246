#include "touchcloud/planning/footprint_choice.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include <Eigen/Cholesky>

#include "touchcloud/error.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/planning/touch_choice.hpp"

namespace touchcloud::planning {

namespace {

std::string at(const Eigen::MatrixX2d& xy, Eigen::Index i) {
  std::ostringstream s;
  s << "(" << xy(i, 0) << ", " << xy(i, 1) << ") mm";
  return s.str();
}

// The model's covariance at the cell centres, checked entry by entry: a value
// that is not finite, or a negative variance, stops the choice here.
Eigen::MatrixXd checked_covariance(const SurfaceModel& surface, const Eigen::MatrixX2d& centres) {
  std::optional<Eigen::MatrixXd> s = surface.covariance(centres);
  if (!s)
    throw RunError("the surface model gives no posterior covariance, which the footprint_variance_reduction "
                   "strategy needs (gp_surface's exact and sparse models give it)");
  const Eigen::Index m = centres.rows();
  if (s->rows() != m || s->cols() != m)
    throw RunError("the surface model returned a " + std::to_string(s->rows()) + " x " + std::to_string(s->cols()) +
                   " covariance for " + std::to_string(m) + " positions");
  for (Eigen::Index j = 0; j < m; ++j) {
    for (Eigen::Index i = 0; i < m; ++i)
      if (!std::isfinite((*s)(i, j)))
        throw RunError("the surface model gave covariance " + number_text((*s)(i, j)) + " mm^2 between " +
                       at(centres, i) + " and " + at(centres, j));
    if ((*s)(j, j) < 0)
      throw RunError("the surface model gave variance " + number_text((*s)(j, j)) + " mm^2 at " + at(centres, j));
  }
  return std::move(*s);
}

}  // namespace

std::vector<Eigen::Index> likely_contact(const Eigen::MatrixX2d& centres, const Eigen::VectorXd& mean_mm,
                                         const Eigen::Vector2d& centre, const PressFootprint& press) {
  const double r = press.gel_radius_mm;
  std::vector<Eigen::Index> disc;
  std::vector<double> reach;  // mean minus the dome's rise above its apex
  for (Eigen::Index i = 0; i < centres.rows(); ++i) {
    const double rho2 = (centres.row(i).transpose() - centre).squaredNorm();
    if (rho2 >= r * r) continue;
    disc.push_back(i);
    reach.push_back(mean_mm[i] - (r - std::sqrt(r * r - rho2)));
  }
  std::vector<Eigen::Index> contact;
  if (disc.empty()) return contact;
  const double first = *std::max_element(reach.begin(), reach.end());
  for (std::size_t k = 0; k < disc.size(); ++k)
    if (reach[k] >= first - press.press_depth_mm) contact.push_back(disc[k]);
  return contact;
}

FootprintChoice footprint_variance_reduction_cell(const SurfaceModel& surface, const WorkspaceGrid& grid,
                                                  const PressFootprint& press, const std::set<int>& avoid) {
  check_choice_grid(grid);
  if (!(press.gel_radius_mm > 0) || !std::isfinite(press.gel_radius_mm))
    throw InputError("the gel radius must be a positive number of mm, not " + number_text(press.gel_radius_mm));
  if (!(press.press_depth_mm >= 0) || !std::isfinite(press.press_depth_mm))
    throw InputError("the press depth must be a number of mm >= 0, not " + number_text(press.press_depth_mm));

  const Eigen::MatrixX2d centres = grid.cell_centres_mm();
  const Eigen::Index m = centres.rows();
  const Eigen::MatrixXd s = checked_covariance(surface, centres);
  // The mean (for the contact) from what the covariance just brought up to
  // date: no pass over all the training data.
  const Eigen::VectorXd mean = surface.candidate_mean(centres);
  for (Eigen::Index i = 0; i < m; ++i)
    if (!std::isfinite(mean[i]))
      throw RunError("the surface model gave mean " + number_text(mean[i]) + " mm at " + at(centres, i));

  const double total = s.trace();
  // The press observes its points with the model's noise; a floor keeps the
  // small system positive definite where the data already pin the surface.
  const double floor = 1e-9 * std::max(1.0, s.diagonal().maxCoeff());
  const double noise = std::max(surface.noise_variance_mm2().value_or(0.0), floor);
  const bool all_avoided = static_cast<int>(avoid.size()) >= grid.cells();

  FootprintChoice best;
  double best_reduction = -1;
  for (int c = 0; c < grid.cells(); ++c) {
    if (!all_avoided && avoid.count(c)) continue;
    const std::vector<Eigen::Index> f = likely_contact(centres, mean, grid.cell_centre_mm(c), press);
    double reduction = 0;
    if (!f.empty()) {
      Eigen::MatrixXd sff = s(f, f);
      sff.diagonal().array() += noise;
      const Eigen::LLT<Eigen::MatrixXd> llt(sff);
      if (llt.info() != Eigen::Success)
        throw RunError("the posterior covariance of the " + std::to_string(f.size()) +
                       " points a press at cell " + std::to_string(c) + " would touch is not positive semi-definite");
      Eigen::MatrixXd w = s(f, Eigen::all);
      llt.matrixL().solveInPlace(w);
      reduction = w.squaredNorm();
      if (!std::isfinite(reduction))
        throw RunError("the variance a press at cell " + std::to_string(c) + " would take away is not finite");
    }
    if (reduction > best_reduction) {
      best_reduction = reduction;
      best.cell = c;
      best.footprint_points = static_cast<int>(f.size());
    }
  }
  best.variance_mm2 = s(best.cell, best.cell);
  best.mean_variance_mm2 = total / static_cast<double>(m);
  best.expected_mean_variance_mm2 = std::max(0.0, total - best_reduction) / static_cast<double>(m);
  return best;
}

}  // namespace touchcloud::planning
