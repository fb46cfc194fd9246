#include "touchcloud/gp/sparse_implicit_surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>

#include "implicit_selection.hpp"
#include "latent_variance.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/parallel_ranges.hpp"

namespace touchcloud::gp {

namespace {

constexpr Eigen::Index kInducingQueryBlock = 256;  // variance: L_uu^-1 K(U, block) holds m x this many doubles
// K_uu's diagonal gets at least this times the signal variance: neighbouring
// inducing points (a pair is 2 offsets apart) at a scale of tens of mm make
// K_uu nearly singular, and L_uu^-1 would amplify rounding into A.
constexpr double kInducingJitterRelative = 1e-6;

// Grows `m` to at least rows x cols (doubling), keeping its used corner.
void reserve_corner(Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols, Eigen::Index used_rows, Eigen::Index used_cols) {
  if (m.rows() >= rows && m.cols() >= cols) return;
  Eigen::MatrixXd grown(std::max(rows, 2 * m.rows()), std::max(cols, 2 * m.cols()));
  grown.topLeftCorner(used_rows, used_cols) = m.topLeftCorner(used_rows, used_cols);
  m.swap(grown);
}

}  // namespace

void SparseImplicitOptions::validate() const {
  if (!(inducing_spacing_mm > 0) || !std::isfinite(inducing_spacing_mm)) {
    std::ostringstream msg;
    msg << "sparse implicit surface option inducing_spacing_mm = " << inducing_spacing_mm << " must be finite and > 0";
    throw InputError(msg.str());
  }
}

SparseImplicitSurface::SparseImplicitSurface(ImplicitSurfaceOptions options, SparseImplicitOptions sparse)
    : options_(std::move(options)), sparse_(sparse) {
  options_.validate();
  sparse_.validate();
}

ImplicitUpdate SparseImplicitSurface::add(const ImplicitTouch& touch) {
  const std::string where = "sparse implicit surface, touch " + std::to_string(touches_ + 1);
  ImplicitUpdate update;
  const Eigen::MatrixX3d normals = checked_touch_normals(touch, data_.contacts, where, update.normals_estimated);
  const Eigen::Index from = data_.n, inducing_from = m_;
  append_implicit_training(touch, normals, options_, data_);
  ++touches_;
  update.points_added = data_.n - from;
  add_sites(from, touch.points_mm.rows());
  const bool first = selected_at_ == 0;
  const bool grown = static_cast<double>(data_.n) >= (1 + options_.reselect_growth) * static_cast<double>(selected_at_);
  const bool covers = options_.kernel != ImplicitKernelKind::thin_plate || data_.diameter_mm() <= h_.lengthscale_mm;
  if (first || grown || !covers) {
    centre_ = data_.contacts.colwise().mean().transpose();
    radius_ = (data_.contacts.rowwise() - centre_.transpose()).rowwise().norm().mean();
    const SearchResult result = select_implicit_on_training(data_, centre_, radius_, options_, update.selection_points);
    h_ = result.hyperparameters;
    selected_at_ = data_.n;
    update.lml = result.lml;
    update.path = ImplicitUpdatePath::selected;
    rebuild();
  } else if (extend_inducing(inducing_from)) {
    add_columns(from);
    update.path = ImplicitUpdatePath::bordered;
  } else {
    rebuild();
    update.path = ImplicitUpdatePath::refactorised;
  }
  solve_weights();
  update.training_points = data_.n;
  update.jitter_mm2 = jitter_mm2_;
  return update;
}

void SparseImplicitSurface::add_sites(Eigen::Index from, Eigen::Index contacts) {
  const double spacing2 = sparse_.inducing_spacing_mm * sparse_.inducing_spacing_mm;
  for (Eigen::Index i = 0; i < contacts; i += options_.offset_stride) {
    const Eigen::Vector3d c = data_.x.row(from + i).transpose();
    if (std::any_of(sites_.begin(), sites_.end(), [&](const Eigen::Vector3d& s) { return (s - c).squaredNorm() < spacing2; }))
      continue;
    sites_.push_back(c);
    if (u_.rows() < m_ + 2) u_.conservativeResize(std::max<Eigen::Index>(2 * u_.rows(), m_ + 2), 3);
    const Eigen::Index pair = from + contacts + 2 * (i / options_.offset_stride);  // as append_implicit_training lays it out
    u_.middleRows(m_, 2) = data_.x.middleRows(pair, 2);
    m_ += 2;
  }
}

void SparseImplicitSurface::rebuild() {
  const ImplicitKernel kernel(options_.kernel, h_);
  const double sigma = std::sqrt(h_.noise_variance_mm2), floor = kInducingJitterRelative * h_.signal_variance_mm2;
  const Eigen::Index n = data_.n;
  reserve_corner(l_uu_, u_.rows(), u_.rows(), 0, 0);
  const CholeskyReport report = factor_with_jitter(
      l_uu_.topLeftCorner(m_, m_),
      [&](Eigen::Ref<Eigen::MatrixXd> out) {
        for (Eigen::Index j = 0; j < m_; ++j)
          for (Eigen::Index i = j; i < m_; ++i) out(i, j) = kernel.covariance((u_.row(i) - u_.row(j)).norm());
        out.diagonal().array() += floor;
      },
      options_.jitter, "sparse implicit surface inducing covariance");
  jitter_mm2_ = floor + report.jitter_mm2;
  reserve_corner(a_, u_.rows(), data_.x.rows(), 0, 0);
  auto a = a_.topLeftCorner(m_, n);
  a = kernel.cross(u_.topRows(m_), data_.x.topRows(n)) / sigma;
  l_uu_.topLeftCorner(m_, m_).triangularView<Eigen::Lower>().solveInPlace(a);
  reserve_corner(b_, u_.rows(), u_.rows(), 0, 0);
  auto b = b_.topLeftCorner(m_, m_);
  b.setIdentity();
  b.selfadjointView<Eigen::Lower>().rankUpdate(a);
  Eigen::VectorXd r(n);
  for (Eigen::Index i = 0; i < n; ++i) r[i] = data_.f[i] - prior(data_.x.row(i).transpose());
  az_ = a * r / sigma;
  columns_ = n;
}

bool SparseImplicitSurface::extend_inducing(Eigen::Index from) {
  const Eigen::Index k = m_ - from;
  if (k == 0) return true;
  if (from == 0) return false;
  const ImplicitKernel kernel(options_.kernel, h_);
  const double sigma = std::sqrt(h_.noise_variance_mm2);
  const auto l11 = l_uu_.topLeftCorner(from, from).triangularView<Eigen::Lower>();
  const Eigen::MatrixXd l21t = l11.solve(kernel.cross(u_.topRows(from), u_.middleRows(from, k)));  // L11^-1 K12
  Eigen::MatrixXd s = kernel.cross(u_.middleRows(from, k), u_.middleRows(from, k)) - l21t.transpose() * l21t;
  s.diagonal().array() += jitter_mm2_;
  Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd l22 = llt.matrixL();
  if (!pivots_above_rounding(l22, h_.signal_variance_mm2 + jitter_mm2_, m_)) return false;
  reserve_corner(l_uu_, m_, m_, from, from);
  l_uu_.block(from, 0, k, from) = l21t.transpose();
  l_uu_.block(from, from, k, k) = l22;
  // The new rows of A: L22^-1 (K(new, X) / s - L21 A1), over the columns A has.
  const Eigen::Index n = columns_;
  reserve_corner(a_, m_, n, from, n);
  const auto a1 = a_.topLeftCorner(from, n);
  Eigen::MatrixXd a2 = kernel.cross(u_.middleRows(from, k), data_.x.topRows(n)) / sigma - l21t.transpose() * a1;
  l22.triangularView<Eigen::Lower>().solveInPlace(a2);
  a_.block(from, 0, k, n) = a2;
  reserve_corner(b_, m_, m_, from, from);
  b_.block(from, 0, k, from) = a2 * a1.transpose();
  b_.block(from, from, k, k) = a2 * a2.transpose();
  b_.block(from, from, k, k).diagonal().array() += 1.0;
  Eigen::VectorXd r(n);
  for (Eigen::Index i = 0; i < n; ++i) r[i] = data_.f[i] - prior(data_.x.row(i).transpose());
  az_.conservativeResize(m_);
  az_.tail(k) = a2 * r / sigma;
  return true;
}

void SparseImplicitSurface::add_columns(Eigen::Index from) {
  const ImplicitKernel kernel(options_.kernel, h_);
  const double sigma = std::sqrt(h_.noise_variance_mm2);
  const Eigen::Index k = data_.n - from;
  reserve_corner(a_, m_, data_.n, m_, from);
  auto a = a_.block(0, from, m_, k);
  a = kernel.cross(u_.topRows(m_), data_.x.middleRows(from, k)) / sigma;
  l_uu_.topLeftCorner(m_, m_).triangularView<Eigen::Lower>().solveInPlace(a);
  b_.topLeftCorner(m_, m_).selfadjointView<Eigen::Lower>().rankUpdate(a);
  Eigen::VectorXd r(k);
  for (Eigen::Index i = 0; i < k; ++i) r[i] = data_.f[from + i] - prior(data_.x.row(from + i).transpose());
  az_ += a * r / sigma;
  columns_ = data_.n;
}

void SparseImplicitSurface::solve_weights() {
  Eigen::LLT<Eigen::MatrixXd> llt(b_.topLeftCorner(m_, m_));  // its lower triangle
  if (llt.info() != Eigen::Success)  // I + A A^T has eigenvalues >= 1: only corrupt input fails
    throw RunError("sparse implicit surface: Cholesky of I + A A^T failed (" + std::to_string(m_) + " inducing points)");
  l_b_ = llt.matrixL();
  weights_ = l_b_.triangularView<Eigen::Lower>().solve(az_);
  l_b_.triangularView<Eigen::Lower>().transpose().solveInPlace(weights_);
  l_uu_.topLeftCorner(m_, m_).triangularView<Eigen::Lower>().transpose().solveInPlace(weights_);
  if (!weights_.allFinite())
    throw RunError("sparse implicit surface: the weights of " + std::to_string(m_) + " inducing points are not finite");
}

void SparseImplicitSurface::require_touches() const {
  if (data_.n == 0) throw InputError("sparse implicit surface: no touches yet, nothing to predict from");
}

Eigen::VectorXd SparseImplicitSurface::mean(const Eigen::Ref<const Eigen::MatrixX3d>& q, int threads) const {
  require_touches();
  const ImplicitKernel kernel(options_.kernel, h_);
  const Eigen::Matrix3Xd u = u_.topRows(m_).transpose();  // a point per column: contiguous
  Eigen::VectorXd out(q.rows());
  for_each_block(static_cast<std::size_t>(q.rows()), resolve_threads(threads), 64, [&](std::size_t begin, std::size_t end) {
    for (auto j = static_cast<Eigen::Index>(begin); j < static_cast<Eigen::Index>(end); ++j) {
      const Eigen::Vector3d p = q.row(j).transpose();
      double sum = prior(p);
      for (Eigen::Index i = 0; i < m_; ++i) sum += weights_[i] * kernel.covariance((u.col(i) - p).norm());
      out[j] = sum;
    }
  });
  return out;
}

Eigen::VectorXd SparseImplicitSurface::variance(const Eigen::Ref<const Eigen::MatrixX3d>& q, std::size_t* clamped) const {
  require_touches();
  const ImplicitKernel kernel(options_.kernel, h_);
  const auto l_uu = l_uu_.topLeftCorner(m_, m_).triangularView<Eigen::Lower>();
  const auto l_b = l_b_.triangularView<Eigen::Lower>();
  Eigen::VectorXd out(q.rows());
  for (Eigen::Index first = 0; first < q.rows(); first += kInducingQueryBlock) {
    const Eigen::Index b = std::min(kInducingQueryBlock, q.rows() - first);
    Eigen::MatrixXd w = l_uu.solve(kernel.cross(u_.topRows(m_), q.middleRows(first, b)));  // L_uu^-1 K_u*
    out.segment(first, b) = h_.signal_variance_mm2 - w.colwise().squaredNorm().transpose().array();
    l_b.solveInPlace(w);  // L_B^-1 L_uu^-1 K_u*
    out.segment(first, b) += w.colwise().squaredNorm().transpose();
  }
  const std::size_t below = clamp_latent_variance(out, "sparse implicit surface", data_.n);
  if (clamped) *clamped = below;
  return out;
}

}  // namespace touchcloud::gp
