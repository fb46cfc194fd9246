#include "touchcloud/gp/implicit_surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "implicit_selection.hpp"
#include "latent_variance.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/parallel_ranges.hpp"

namespace touchcloud::gp {

namespace {

constexpr Eigen::Index kQueryBlock = 256;  // variance: L^-1 K(X, block) holds n x this many doubles

// Singular values of the centred points, largest first.
Eigen::Vector3d implicit_spread_of(const Eigen::MatrixX3d& p) {
  if (p.rows() < 2) return Eigen::Vector3d::Zero();
  const Eigen::MatrixX3d c = p.rowwise() - p.colwise().mean();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c.transpose() * c);
  return eig.eigenvalues().reverse().cwiseMax(0.0).cwiseSqrt();
}

// The patch's plane normal (its least spread direction), turned away from `centroid`.
Eigen::Vector3d implicit_patch_normal(const Eigen::MatrixX3d& p, const Eigen::Vector3d& centroid) {
  const Eigen::RowVector3d mean = p.colwise().mean();
  const Eigen::MatrixX3d c = p.rowwise() - mean;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c.transpose() * c);
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  if (n.dot(mean.transpose() - centroid) < 0) n = -n;
  return n;
}

}  // namespace

Eigen::MatrixX3d checked_touch_normals(const ImplicitTouch& touch, const Eigen::MatrixX3d& contacts,
                                       const std::string& where, bool& estimated) {
  const Eigen::Index k = touch.points_mm.rows();
  if (k == 0) throw InputError(where + ": no points");
  if (!touch.points_mm.allFinite()) throw InputError(where + ": a point is not finite");
  if (touch.free_distance_mm.size() != touch.free_mm.rows())
    throw InputError(where + ": " + std::to_string(touch.free_distance_mm.size()) + " distances for " +
                     std::to_string(touch.free_mm.rows()) + " swept points");
  if (!touch.free_mm.allFinite()) throw InputError(where + ": a swept point is not finite");
  for (Eigen::Index i = 0; i < touch.free_distance_mm.size(); ++i)
    if (!(touch.free_distance_mm[i] > 0) || !std::isfinite(touch.free_distance_mm[i]))
      throw InputError(where + ": swept point " + std::to_string(i) + " has distance " +
                       std::to_string(touch.free_distance_mm[i]) + " (finite and > 0 expected: it is outside)");
  estimated = false;
  Eigen::MatrixX3d normals = touch.normals;
  if (normals.rows() == 0) {
    // No normals: the side comes from the patch's plane and the centroid of all points.
    Eigen::MatrixX3d all(contacts.rows() + k, 3);
    all << contacts, touch.points_mm;
    const Eigen::Vector3d own = implicit_spread_of(touch.points_mm), whole = implicit_spread_of(all);
    if (!(own[1] > 1e-6 * own[0]))
      throw InputError(where + ": its " + std::to_string(k) + " points are " + (own[0] > 0 ? "collinear" : "one point") +
                       " and carry no normals: the side of the surface they face is unknown");
    const Eigen::Vector3d centroid = all.colwise().mean().transpose();
    const Eigen::Vector3d n = implicit_patch_normal(touch.points_mm, centroid);
    const double off_plane = n.dot(touch.points_mm.colwise().mean().transpose() - centroid);
    if (!(off_plane > 1e-3 * whole[0]))
      throw InputError(where + ": the " + std::to_string(all.rows()) +
                       " points touched so far lie about the plane of this touch, which carries no normals: inside "
                       "and outside cannot be told apart");
    normals = n.transpose().replicate(k, 1);
    estimated = true;
  } else {
    if (normals.rows() != k)
      throw InputError(where + ": " + std::to_string(normals.rows()) + " normals for " + std::to_string(k) + " points");
    for (Eigen::Index i = 0; i < k; ++i) {
      const double len = normals.row(i).norm();
      if (!std::isfinite(len) || std::abs(len - 1) > 1e-6)
        throw InputError(where + ": the normal of point " + std::to_string(i) + " has length " + std::to_string(len) +
                         " (unit length expected)");
    }
  }
  return normals;
}

void append_implicit_training(const ImplicitTouch& touch, const Eigen::MatrixX3d& normals, const ImplicitSurfaceOptions& options,
                              ImplicitTraining& t) {
  const Eigen::Index k = touch.points_mm.rows();
  const Eigen::Index add = implicit_rows_of(touch, options);
  if (t.x.rows() < t.n + add) {
    const Eigen::Index capacity = std::max<Eigen::Index>(2 * t.x.rows(), t.n + add);
    t.x.conservativeResize(capacity, 3);
    t.f.conservativeResize(capacity);
  }
  t.x.middleRows(t.n, k) = touch.points_mm;
  t.f.segment(t.n, k).setZero();
  Eigen::Index row = t.n + k;
  for (Eigen::Index i = 0; i < k; i += options.offset_stride)
    for (const double side : {1.0, -1.0}) {
      t.x.row(row) = touch.points_mm.row(i) + side * options.offset_mm * normals.row(i);
      t.f[row++] = side * options.offset_mm;
    }
  const Eigen::Index swept = touch.free_mm.rows();
  t.x.middleRows(row, swept) = touch.free_mm;
  t.f.segment(row, swept) = touch.free_distance_mm;
  t.n = row + swept;
  t.contacts.conservativeResize(t.contacts.rows() + k, 3);
  t.contacts.bottomRows(k) = touch.points_mm;
}

Eigen::Index implicit_rows_of(const ImplicitTouch& touch, const ImplicitSurfaceOptions& options) {
  const Eigen::Index k = touch.points_mm.rows();
  return k + 2 * ((k + options.offset_stride - 1) / options.offset_stride) + touch.free_mm.rows();
}

void add_swept_approach(ImplicitTouch& touch, const Eigen::Vector3d& contact_mm, const Eigen::Vector3d& outward,
                        double length_mm, double step_mm) {
  if (!(step_mm > 0) || !(length_mm >= 0) || !std::isfinite(length_mm) || !contact_mm.allFinite() ||
      std::abs(outward.norm() - 1) > 1e-6)
    throw InputError("swept approach: the contact must be finite, the direction unit length, the step > 0 and the "
                     "length finite and >= 0");
  const auto steps = static_cast<Eigen::Index>(std::floor(length_mm / step_mm + 1e-9));
  const Eigen::Index from = touch.free_mm.rows();
  touch.free_mm.conservativeResize(from + steps, 3);
  touch.free_distance_mm.conservativeResize(from + steps);
  for (Eigen::Index i = 0; i < steps; ++i) {
    const double s = step_mm * static_cast<double>(i + 1);
    touch.free_mm.row(from + i) = (contact_mm + s * outward).transpose();
    touch.free_distance_mm[from + i] = s;
  }
}

double ImplicitTraining::diameter_mm() const {
  const Eigen::MatrixX3d p = x.topRows(n);
  return (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
}

std::string to_string(ImplicitUpdatePath path) {
  switch (path) {
    case ImplicitUpdatePath::selected: return "selected";
    case ImplicitUpdatePath::bordered: return "bordered";
    case ImplicitUpdatePath::refactorised: return "refactorised";
  }
  return "?";
}

void ImplicitSurfaceOptions::validate() const {
  auto fail = [](const std::string& field, double value, const char* rule) {
    std::ostringstream msg;
    msg << "implicit surface option " << field << " = " << value << " must be " << rule;
    throw InputError(msg.str());
  };
  if (!(offset_mm > 0) || !std::isfinite(offset_mm)) fail("offset_mm", offset_mm, "finite and > 0");
  if (offset_stride < 1) fail("offset_stride", offset_stride, ">= 1");
  if (selection_points < 3) fail("selection_points", static_cast<double>(selection_points), ">= 3");
  if (!(reselect_growth >= 0) || !std::isfinite(reselect_growth)) fail("reselect_growth", reselect_growth, "finite and >= 0");
  if (!(max_noise_mm > 0) || !std::isfinite(max_noise_mm)) fail("max_noise_mm", max_noise_mm, "finite and > 0");
  if (!(min_noise_mm > 0) || !(min_noise_mm <= max_noise_mm)) fail("min_noise_mm", min_noise_mm, "> 0 and <= max_noise_mm");
  if (max_iterations < 1) fail("max_iterations", max_iterations, ">= 1");
  if (max_training_points && *max_training_points < 1)
    fail("max_training_points", static_cast<double>(*max_training_points), ">= 1 when set");
  jitter.validate();
}

ImplicitTouches::ImplicitTouches(ImplicitSurfaceOptions options) : options_(std::move(options)) {
  options_.validate();
}

bool ImplicitTouches::selects_again() const {
  const bool first = selected_at_ == 0;
  const bool grown = static_cast<double>(data_.n) >= (1 + options_.reselect_growth) * static_cast<double>(selected_at_);
  const bool covers =
      options_.kernel != ImplicitKernelKind::thin_plate || scale_floor_ * data_.diameter_mm() <= h_.lengthscale_mm;
  return first || grown || !covers;
}

bool ImplicitTouches::widen_thin_plate() {
  if (options_.kernel != ImplicitKernelKind::thin_plate || scale_floor_ > 3) return false;
  scale_floor_ *= 1.5;
  return true;
}

double ImplicitTouches::select_on_touches(Eigen::Index& subset_size) {
  centre_ = data_.contacts.colwise().mean().transpose();
  radius_ = (data_.contacts.rowwise() - centre_.transpose()).rowwise().norm().mean();
  const SearchResult result = select_implicit_on_training(data_, centre_, radius_, options_, scale_floor_, subset_size);
  h_ = result.hyperparameters;
  selected_at_ = data_.n;
  return result.lml;
}

ImplicitSurface::ImplicitSurface(ImplicitSurfaceOptions options) : ImplicitTouches(std::move(options)) {}

ImplicitUpdate ImplicitSurface::add(const ImplicitTouch& touch) {
  const std::string where = "implicit surface, touch " + std::to_string(touches_ + 1);
  ImplicitUpdate update;
  const Eigen::MatrixX3d normals = checked_touch_normals(touch, data_.contacts, where, update.normals_estimated);
  const Eigen::Index from = data_.n;
  const Eigen::Index adding = implicit_rows_of(touch, options_);
  if (options_.max_training_points && data_.n + adding > *options_.max_training_points)
    throw InputError(where + ": " + std::to_string(data_.n + adding) + " training points would exceed the exact form's " +
                     std::to_string(*options_.max_training_points) + " (max_training_points): use the sparse form");
  append_implicit_training(touch, normals, options_, data_);
  ++touches_;
  update.points_added = data_.n - from;
  if (selects_again()) {
    select_and_factorise(update);
  } else if (extend_factor(from)) {
    update.path = ImplicitUpdatePath::bordered;
  } else {
    update.path = ImplicitUpdatePath::refactorised;
    if (!factorised()) select_and_factorise(update);
  }
  solve_weights();
  update.training_points = data_.n;
  update.jitter_mm2 = jitter_mm2_;
  update.scale_floor = scale_floor_;
  return update;
}

bool ImplicitSurface::factorised() {
  try {
    refactorise();
    return true;
  } catch (const RunError& e) {
    if (!widen_thin_plate())
      throw RunError(std::string(e.what()) +
                     (options_.kernel == ImplicitKernelKind::thin_plate
                          ? " at every thin-plate R tried (up to 3.4 times the data's diameter): use a Matern kernel"
                          : ""));
    return false;
  }
}

void ImplicitSurface::select_and_factorise(ImplicitUpdate& update) {
  do {
    update.lml = select_on_touches(update.selection_points);
    update.path = ImplicitUpdatePath::selected;
  } while (!factorised());
}

void ImplicitSurface::refactorise() {
  const ImplicitKernel kernel(options_.kernel, h_);
  const Eigen::Index capacity = data_.x.rows();
  if (factor_.rows() < capacity) factor_.resize(capacity, capacity);
  const CholeskyReport report = factor_with_jitter(
      factor_.topLeftCorner(data_.n, data_.n),
      [&](Eigen::Ref<Eigen::MatrixXd> out) {
        for (Eigen::Index j = 0; j < data_.n; ++j)
          for (Eigen::Index i = j; i < data_.n; ++i) out(i, j) = kernel.covariance((data_.x.row(i) - data_.x.row(j)).norm());
        out.diagonal().array() += h_.noise_variance_mm2;
      },
      options_.jitter, "implicit surface covariance");
  jitter_mm2_ = report.jitter_mm2;
  Eigen::VectorXd r(data_.n);
  for (Eigen::Index i = 0; i < data_.n; ++i) r[i] = data_.f[i] - prior(data_.x.row(i).transpose());
  v_ = factor_.topLeftCorner(data_.n, data_.n).triangularView<Eigen::Lower>().solve(r);
}

bool ImplicitSurface::extend_factor(Eigen::Index from) {
  const ImplicitKernel kernel(options_.kernel, h_);
  const Eigen::Index k = data_.n - from;
  if (factor_.rows() < data_.n) {
    Eigen::MatrixXd grown(data_.x.rows(), data_.x.rows());
    grown.topLeftCorner(from, from) = factor_.topLeftCorner(from, from);
    factor_.swap(grown);
  }
  const auto l11 = factor_.topLeftCorner(from, from).triangularView<Eigen::Lower>();
  const Eigen::MatrixXd b = l11.solve(kernel.cross(data_.x.topRows(from), data_.x.middleRows(from, k)));  // L11^-1 K12
  Eigen::MatrixXd s = kernel.cross(data_.x.middleRows(from, k), data_.x.middleRows(from, k)) - b.transpose() * b;
  s.diagonal().array() += h_.noise_variance_mm2 + jitter_mm2_;
  Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd l22 = llt.matrixL();
  const double mean_diagonal = h_.signal_variance_mm2 + h_.noise_variance_mm2 + jitter_mm2_;
  if (!pivots_above_rounding(l22, mean_diagonal, data_.n)) return false;
  factor_.block(from, 0, k, from) = b.transpose();
  factor_.block(from, from, k, k) = l22;
  Eigen::VectorXd r(k);
  for (Eigen::Index i = 0; i < k; ++i) r[i] = data_.f[from + i] - prior(data_.x.row(from + i).transpose());
  v_.conservativeResize(data_.n);
  v_.tail(k) = l22.triangularView<Eigen::Lower>().solve(r - b.transpose() * v_.head(from));
  return true;
}

void ImplicitSurface::solve_weights() {
  const Eigen::MatrixXd& factor = factor_;
  alpha_ = factor.topLeftCorner(data_.n, data_.n).triangularView<Eigen::Lower>().transpose().solve(v_);
  if (!alpha_.allFinite())
    throw RunError("implicit surface: the weights of " + std::to_string(data_.n) + " training points are not finite");
}

void ImplicitSurface::require_touches() const {
  if (data_.n == 0) throw InputError("implicit surface: no touches yet, nothing to predict from");
}

Eigen::VectorXd ImplicitSurface::mean(const Eigen::Ref<const Eigen::MatrixX3d>& q, int threads) const {
  require_touches();
  const ImplicitKernel kernel(options_.kernel, h_);
  const auto x = data_.x.topRows(data_.n);
  Eigen::VectorXd out(q.rows());
  // Each query's sum runs over the training points in one order, whatever
  // the block: the same values for any thread count.
  for_each_block(static_cast<std::size_t>(q.rows()), resolve_threads(threads), 64, [&](std::size_t begin, std::size_t end) {
    const auto first = static_cast<Eigen::Index>(begin), count = static_cast<Eigen::Index>(end - begin);
    out.segment(first, count) = kernel.weighted_sums(x, alpha_, q.middleRows(first, count));
    for (Eigen::Index j = first; j < first + count; ++j) out[j] += prior(q.row(j).transpose());
  });
  return out;
}

Eigen::VectorXd ImplicitSurface::variance(const Eigen::Ref<const Eigen::MatrixX3d>& q, std::size_t* clamped) const {
  require_touches();
  const ImplicitKernel kernel(options_.kernel, h_);
  const auto l = factor_.topLeftCorner(data_.n, data_.n).triangularView<Eigen::Lower>();
  Eigen::VectorXd out(q.rows());
  for (Eigen::Index first = 0; first < q.rows(); first += kQueryBlock) {
    const Eigen::Index b = std::min(kQueryBlock, q.rows() - first);
    const Eigen::MatrixXd v = l.solve(kernel.cross(data_.x.topRows(data_.n), q.middleRows(first, b)));
    out.segment(first, b) = h_.signal_variance_mm2 - v.colwise().squaredNorm().transpose().array();
  }
  const std::size_t below = clamp_latent_variance(out, "implicit surface", data_.n);
  if (clamped) *clamped = below;
  return out;
}

}  // namespace touchcloud::gp
