#include "touchcloud/gp/sparse_implicit_surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>

#include "touchcloud/gp/cholesky_inverse.hpp"
#include "touchcloud/gp/factor_algebra.hpp"
#include "latent_variance.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/parallel_ranges.hpp"

namespace touchcloud::gp {

namespace {

constexpr Eigen::Index kInducingQueryBlock = 512;  // variance: K(U, block) and its product hold m x this many doubles each
// New inducing rows: A's columns this many at a time (m x 256 doubles, about
// 1.3 MB at m = 620, stay in cache between the block's two products).
constexpr Eigen::Index kColumnBlock = 256;
// K_uu's diagonal gets at least this times the signal variance: neighbouring
// inducing points (a pair is 2 offsets apart) at a scale of tens of mm make
// K_uu nearly singular, and L_uu^-1 would amplify rounding into A.
constexpr double kInducingJitterRelative = 1e-6;

// Grows `m` to at least rows x cols, keeping its used corner: a dimension
// that must grow grows by half again (amortised O(1) per row or column
// added; A's rows by doubling cost a copy of A in memory and time whenever
// the model is copied), one that need not keeps its size.
void reserve_corner(Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols, Eigen::Index used_rows, Eigen::Index used_cols) {
  if (m.rows() >= rows && m.cols() >= cols) return;
  const auto grow = [](Eigen::Index have, Eigen::Index need) { return have >= need ? have : std::max(need, have + have / 2); };
  Eigen::MatrixXd grown(grow(m.rows(), rows), grow(m.cols(), cols));
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
    : ImplicitTouches(std::move(options)), sparse_(sparse) {
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
  add_sites(from, touch);
  if (selects_again()) {
    update.lml = select_on_touches(update.selection_points);
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

void SparseImplicitSurface::add_sites(Eigen::Index from, const ImplicitTouch& touch) {
  const double spacing2 = sparse_.inducing_spacing_mm * sparse_.inducing_spacing_mm;
  const auto taken = [&](const Eigen::Vector3d& c) {
    return std::any_of(sites_.begin(), sites_.end(), [&](const Eigen::Vector3d& s) { return (s - c).squaredNorm() < spacing2; });
  };
  const auto add = [&](Eigen::Index row, Eigen::Index count) {
    if (u_.rows() < m_ + count) u_.conservativeResize(std::max<Eigen::Index>(2 * u_.rows(), m_ + count), 3);
    u_.middleRows(m_, count) = data_.x.middleRows(row, count);
    m_ += count;
  };
  const Eigen::Index contacts = touch.points_mm.rows();
  for (Eigen::Index i = 0; i < contacts; i += options_.offset_stride) {
    const Eigen::Vector3d c = data_.x.row(from + i).transpose();
    if (taken(c)) continue;
    sites_.push_back(c);
    add(from + contacts + 2 * (i / options_.offset_stride), 2);  // the pair, as append_implicit_training lays it out
  }
  // A swept point where no site is near is a site of its own: the space a gel
  // went through can lie far from any contact (a cup's mouth).
  const Eigen::Index swept_from = data_.n - touch.free_mm.rows();
  for (Eigen::Index i = 0; i < touch.free_mm.rows(); ++i) {
    const Eigen::Vector3d c = touch.free_mm.row(i).transpose();
    if (taken(c)) continue;
    sites_.push_back(c);
    add(swept_from + i, 1);
  }
}

void SparseImplicitSurface::rebuild() {
  const ImplicitKernel kernel(options_.kernel, h_);
  const double sigma = std::sqrt(h_.noise_variance_mm2), floor = kInducingJitterRelative * h_.signal_variance_mm2;
  const Eigen::Index n = data_.n;
  reserve_corner(l_uu_, m_, m_, 0, 0);
  const CholeskyReport report = factor_with_jitter(
      l_uu_.topLeftCorner(m_, m_),
      [&](Eigen::Ref<Eigen::MatrixXd> out) {
        for (Eigen::Index j = 0; j < m_; ++j)
          for (Eigen::Index i = j; i < m_; ++i) out(i, j) = kernel.covariance((u_.row(i) - u_.row(j)).norm());
        out.diagonal().array() += floor;
      },
      options_.jitter, "sparse implicit surface inducing covariance");
  jitter_mm2_ = floor + report.jitter_mm2;
  reserve_corner(a_, m_, n, 0, 0);
  auto a = a_.topLeftCorner(m_, n);
  a = kernel.cross(u_.topRows(m_), data_.x.topRows(n)) / sigma;
  l_uu_.topLeftCorner(m_, m_).triangularView<Eigen::Lower>().solveInPlace(a);
  reserve_corner(b_, m_, m_, 0, 0);
  auto b = b_.topLeftCorner(m_, m_);
  b.setIdentity();
  b.selfadjointView<Eigen::Lower>().rankUpdate(a);
  az_ = a * residuals(0, n) / sigma;
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
  // The new rows of A, L22^-1 (K(new, X) / s - L21 A1), and of B, A2 A1^T,
  // a block of columns at a time: A1 (m x n, the model's bulk) is read from
  // memory once, where two whole products would each read it, at memory's pace.
  const Eigen::Index n = columns_;
  reserve_corner(a_, m_, n, from, n);
  reserve_corner(b_, m_, m_, from, from);
  const Eigen::MatrixXd l21 = l21t.transpose();
  Eigen::MatrixXd b21 = Eigen::MatrixXd::Zero(k, from);
  for (Eigen::Index first = 0; first < n; first += kColumnBlock) {
    const Eigen::Index w = std::min(kColumnBlock, n - first);
    const auto a1 = a_.block(0, first, from, w);
    Eigen::MatrixXd a2 = kernel.cross(u_.middleRows(from, k), data_.x.middleRows(first, w)) / sigma;
    subtract_product(a2, l21, a1);
    l22.triangularView<Eigen::Lower>().solveInPlace(a2);
    a_.block(from, first, k, w) = a2;
    b21 += product_transposed(a2, a1);
  }
  b_.block(from, 0, k, from) = b21;
  const auto a2 = a_.block(from, 0, k, n);
  b_.block(from, from, k, k) = a2 * a2.transpose();
  b_.block(from, from, k, k).diagonal().array() += 1.0;
  az_.conservativeResize(m_);
  az_.tail(k) = a2 * residuals(0, n) / sigma;
  return true;
}

Eigen::VectorXd SparseImplicitSurface::residuals(Eigen::Index first, Eigen::Index count) const {
  Eigen::VectorXd r(count);
  for (Eigen::Index i = 0; i < count; ++i) r[i] = data_.f[first + i] - prior(data_.x.row(first + i).transpose());
  return r;
}

void SparseImplicitSurface::add_columns(Eigen::Index from) {
  const ImplicitKernel kernel(options_.kernel, h_);
  const double sigma = std::sqrt(h_.noise_variance_mm2);
  const Eigen::Index k = data_.n - from;
  reserve_corner(a_, m_, data_.n, m_, from);
  auto a = a_.block(0, from, m_, k);
  a = kernel.cross(u_.topRows(m_), data_.x.middleRows(from, k)) / sigma;
  solve_lower_in_place(l_uu_.topLeftCorner(m_, m_), a);
  add_row_gram_lower(b_.topLeftCorner(m_, m_), a.transpose());
  az_ += a * residuals(from, k) / sigma;
  columns_ = data_.n;
}

void SparseImplicitSurface::solve_weights() {
  l_b_ = b_.topLeftCorner(m_, m_);
  if (!cholesky_lower_in_place(l_b_))  // I + A A^T has eigenvalues >= 1: only corrupt input fails
    throw RunError("sparse implicit surface: Cholesky of I + A A^T failed (" + std::to_string(m_) + " inducing points)");
  weights_ = az_;
  solve_lower_in_place(l_b_, weights_);
  solve_lower_transposed_in_place(l_b_, weights_);
  solve_lower_transposed_in_place(l_uu_.topLeftCorner(m_, m_), weights_);
  if (!weights_.allFinite())
    throw RunError("sparse implicit surface: the weights of " + std::to_string(m_) + " inducing points are not finite");
  // The variance's quadratic form, k^T M k with M = K_uu^-1 - Sigma^-1 and
  // Sigma = L_uu B L_uu^T = (L_uu L_B)(L_uu L_B)^T, kept as the lower
  // triangle of M with its strict part doubled (k^T M k = k^T T k): a block
  // of queries then costs one triangular product, half the flops of the two
  // triangular solves |L_uu^-1 k|^2 - |L_B^-1 L_uu^-1 k|^2.
  const auto l_uu = l_uu_.topLeftCorner(m_, m_);
  Eigen::MatrixXd l_sigma = l_b_.triangularView<Eigen::Lower>();
  multiply_lower_in_place(l_uu, l_sigma);
  cholesky_inverse_in_place(l_sigma);
  variance_form_ = l_uu;
  cholesky_inverse_in_place(variance_form_);
  variance_form_ -= l_sigma;
  variance_form_.triangularView<Eigen::StrictlyLower>() *= 2.0;
}

void SparseImplicitSurface::require_touches() const {
  if (data_.n == 0) throw InputError("sparse implicit surface: no touches yet, nothing to predict from");
}

Eigen::VectorXd SparseImplicitSurface::mean(const Eigen::Ref<const Eigen::MatrixX3d>& q, int threads) const {
  require_touches();
  const ImplicitKernel kernel(options_.kernel, h_);
  const auto u = u_.topRows(m_);
  Eigen::VectorXd out(q.rows());
  for_each_block(static_cast<std::size_t>(q.rows()), resolve_threads(threads), 64, [&](std::size_t begin, std::size_t end) {
    const auto first = static_cast<Eigen::Index>(begin), count = static_cast<Eigen::Index>(end - begin);
    out.segment(first, count) = kernel.weighted_sums(u, weights_, q.middleRows(first, count));
    for (Eigen::Index j = first; j < first + count; ++j) out[j] += prior(q.row(j).transpose());
  });
  return out;
}

Eigen::VectorXd SparseImplicitSurface::variance(const Eigen::Ref<const Eigen::MatrixX3d>& q, std::size_t* clamped) const {
  require_touches();
  const ImplicitKernel kernel(options_.kernel, h_);
  Eigen::VectorXd out(q.rows());
  for (Eigen::Index first = 0; first < q.rows(); first += kInducingQueryBlock) {
    const Eigen::Index b = std::min(kInducingQueryBlock, q.rows() - first);
    const Eigen::MatrixXd k = kernel.cross_vectorised(u_.topRows(m_), q.middleRows(first, b));
    Eigen::MatrixXd tk = k;
    multiply_lower_in_place(variance_form_, tk);
    out.segment(first, b) = h_.signal_variance_mm2 - (k.array() * tk.array()).colwise().sum().transpose();
  }
  const std::size_t below = clamp_latent_variance(out, "sparse implicit surface", data_.n);
  if (clamped) *clamped = below;
  return out;
}

}  // namespace touchcloud::gp
