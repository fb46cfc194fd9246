#include "touchcloud/gp/exact_gp.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <mutex>
#include <numbers>

#include <Eigen/Dense>

#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/gp/huge_pages.hpp"
#include "latent_variance.hpp"
#include "touchcloud/gp/vector_exp.hpp"

#include "touchcloud/error.hpp"

namespace touchcloud::gp {

std::string to_string(UpdatePath path) { return path == UpdatePath::bordered ? "bordered" : "refactorised"; }

// L for every model of one lineage: rows [0, claimed) were written by the
// newest model; a model of n points reads only the lower n x n corner.
struct ExactGp::FactorStore {
  // Rows from `in_use` on, and the columns above them, are written here,
  // once, so that the pages later touches' bordered updates write (new rows
  // across every column, and their mirror as work space) are faulted in now
  // rather than during an update; with huge pages (huge_pages.hpp) that
  // is a few dozen faults for the whole store.
  FactorStore(Eigen::Index capacity, Eigen::Index in_use) : l(capacity, capacity) {
    advise_huge_pages(l);
    const Eigen::Index used = std::min(in_use, capacity);
    l.bottomRows(capacity - used).setZero();
    l.topRightCorner(used, capacity - used).setZero();
  }
  Eigen::MatrixXd l;  // capacity x capacity
  std::mutex mutex;   // guards claimed and the candidate cache
  Eigen::Index claimed = 0;
  // Candidate cache: rows [0, v_rows) of V = L^-1 K(X, C) for C = candidates_mm,
  // and the squared norms of its columns over those rows.
  Eigen::MatrixX2d candidates_mm{0, 2};
  Eigen::MatrixXd v;  // capacity x m
  Eigen::Index v_rows = 0;
  Eigen::RowVectorXd v_norms;
  // V^T V over rows [0, gram_rows), for the posterior covariance among the
  // candidates; extended from the cached rows only when asked for.
  Eigen::MatrixXd gram;
  Eigen::Index gram_rows = 0;
};

ExactGp::ExactGp(KernelKind kind, const Hyperparameters& h, ExactGpOptions options)
    : kernel_(kind, h),
      options_(options),
      store_(std::make_shared<FactorStore>(0, 0)),
      weights_(std::make_shared<Weights>()) {
  options_.jitter.validate();
}

Eigen::Block<Eigen::MatrixXd> ExactGp::factor() { return store_->l.topLeftCorner(n_, n_); }
Eigen::Block<const Eigen::MatrixXd> ExactGp::factor() const {
  const Eigen::MatrixXd& l = store_->l;
  return l.topLeftCorner(n_, n_);
}

Eigen::Index ExactGp::capacity() const { return store_->l.rows(); }

Eigen::Index ExactGp::capacity_for(Eigen::Index points) const {
  return points + static_cast<Eigen::Index>(options_.capacity_slack * static_cast<double>(points));
}

void ExactGp::fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm) {
  check_training(xy_mm, z_mm, "training point");
  const bool any = xy_mm.rows() > 0;
  fit(xy_mm, z_mm, any ? centring_of(xy_mm, z_mm, options_.prior_mean) : Centring{});
  centring_fixed_ = any;
}

void ExactGp::fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, const Centring& centring) {
  check_training(xy_mm, z_mm, "training point");
  centring_ = centring;
  centring_fixed_ = true;
  CentredXy p = centre(xy_mm, centring_);
  x_ = std::move(p.x);
  y_ = std::move(p.y);
  z_ = z_mm.array() - centring_.z_mm;
  n_ = xy_mm.rows();
  refactorise();
}

void ExactGp::refactorise() {
  const double noise = kernel_.hyperparameters().noise_variance_mm2;
  // Never in place: other snapshots may read the current store.
  store_ = std::make_shared<FactorStore>(std::max(capacity(), capacity_for(n_)), n_);
  store_->claimed = n_;
  try {
    factorisation_ = factor_with_jitter(
        factor(), [&](Eigen::Ref<Eigen::MatrixXd> a) { kernel_.fill_lower(x_, y_, noise, a); }, options_.jitter,
        "GP surface fit");
  } catch (const RunError&) {
    // Fall back to the prior rather than keep a model that would answer from garbage.
    n_ = 0;
    x_.resize(0);
    y_.resize(0);
    z_.resize(0);
    v_.resize(0);
    weights_ = std::make_shared<Weights>();
    factorisation_ = {};
    store_ = std::make_shared<FactorStore>(0, 0);
    throw;
  }
  v_ = z_;
  solve_lower_in_place(factor(), v_);
  weights_ = std::make_shared<Weights>();
}

void ExactGp::move_to_new_store(Eigen::Index capacity) {
  auto grown = std::make_shared<FactorStore>(std::max(capacity, n_), n_);
  grown->l.topLeftCorner(n_, n_).triangularView<Eigen::Lower>() = factor().triangularView<Eigen::Lower>();
  grown->claimed = n_;
  {
    std::lock_guard<std::mutex> lock(store_->mutex);  // the cache's rows below n_ stay valid for this lineage
    const Eigen::Index rows = std::min(store_->v_rows, n_);
    if (rows > 0) {
      grown->candidates_mm = store_->candidates_mm;
      grown->v.resize(grown->l.rows(), store_->v.cols());
      advise_huge_pages(grown->v);
      grown->v.topRows(rows) = store_->v.topRows(rows);
      grown->v_rows = rows;
      grown->v_norms = rows == store_->v_rows ? store_->v_norms : grown->v.topRows(rows).colwise().squaredNorm();
      if (store_->gram_rows > 0 && store_->gram_rows <= rows) {
        grown->gram = store_->gram;
        grown->gram_rows = store_->gram_rows;
      }
    }
  }
  store_ = std::move(grown);
}

void ExactGp::reserve(Eigen::Index points) {
  if (points > capacity()) move_to_new_store(points);
}

void ExactGp::claim_rows(Eigen::Index k) {
  {
    std::lock_guard<std::mutex> lock(store_->mutex);
    if (store_->claimed == n_ && n_ + k <= capacity()) {
      store_->claimed = n_ + k;
      return;
    }
  }
  move_to_new_store(std::max(capacity(), capacity_for(n_ + k)));
  store_->claimed = n_ + k;
}

UpdateReport ExactGp::add_points(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm) {
  check_training(xy_mm, z_mm, "added training point");
  const Eigen::Index k = xy_mm.rows(), n = n_;
  UpdateReport report;
  report.points_added = k;
  report.factorisation = factorisation_;
  if (k == 0) return report;

  if (!centring_fixed_) centring_ = centring_of(xy_mm, z_mm);
  centring_fixed_ = true;
  const CentredXy p = centre(xy_mm, centring_);
  const Eigen::VectorXd zc = z_mm.array() - centring_.z_mm;

  bool extended = false;
  if (n > 0) {
    claim_rows(k);
    // [L 0; L21 L22] with L21 = K21 L^-T and L22 L22^T = A22 - L21 L21^T
    // (the Schur complement). K21 is written straight into the new rows and
    // solved there from the right, or (left_side_update) its transpose is
    // solved from the left in the store's unused upper triangle (the new
    // rows' mirror, written when the store was made) and copied in.
    Eigen::MatrixXd& storage = store_->l;
    const double s2 = kernel_.hyperparameters().signal_variance_mm2;
    const double noise = kernel_.hyperparameters().noise_variance_mm2;
    auto l21 = storage.block(n, 0, k, n);
    if (options_.left_side_update.value_or(left_side_solve_preferred(n))) {
      auto l21_t = storage.block(0, n, n, k);
      kernel_.fill_cross(x_, y_, p.x, p.y, l21_t);
      solve_lower_in_place(storage.topLeftCorner(n, n), l21_t);
      l21 = l21_t.transpose();
    } else {
      kernel_.fill_cross(p.x, p.y, x_, y_, l21);
      solve_right_lower_transposed_in_place(storage.topLeftCorner(n, n), l21);
    }
    auto schur = storage.block(n, n, k, k);
    kernel_.fill_lower(p.x, p.y, noise + factorisation_.jitter_mm2, schur);
    subtract_gram_lower(schur, l21);
    extended = cholesky_lower_in_place(schur) && pivots_above_rounding(schur, s2 + noise, n + k);
    if (extended) {
      Eigen::VectorXd v_new = zc - l21 * v_;
      solve_lower_in_place(schur, v_new);
      v_.conservativeResize(n + k);
      v_.tail(k) = v_new;
    }
  }

  x_.conservativeResize(n + k);
  y_.conservativeResize(n + k);
  z_.conservativeResize(n + k);
  x_.tail(k) = p.x;
  y_.tail(k) = p.y;
  z_.tail(k) = zc;
  n_ = n + k;

  if (extended) {
    weights_ = std::make_shared<Weights>();
    report.path = UpdatePath::bordered;
  } else {
    refactorise();
    report.path = UpdatePath::refactorised;
    report.reason = n == 0 ? "no earlier factor to extend"
                           : "the Schur complement of the new points is not positive definite "
                             "(e.g. a new point duplicates the data to rounding level)";
  }
  report.factorisation = factorisation_;
  return report;
}

Eigen::Index ExactGp::query_block() const {
  return std::max<Eigen::Index>(1, options_.query_block_doubles / std::max<Eigen::Index>(1, n_));
}

void ExactGp::for_each_cross_block(const Eigen::MatrixX2d& xy_mm, const CrossBlockFunction& f) const {
  const Eigen::Index m = xy_mm.rows();
  if (n_ == 0 || m == 0) return;
  const Eigen::Index block = std::min(query_block(), m);
  Eigen::MatrixXd k_cross(n_, block);
  for (Eigen::Index b0 = 0; b0 < m; b0 += block) {
    const Eigen::Index bs = std::min(block, m - b0);
    const Eigen::VectorXd qx = xy_mm.col(0).segment(b0, bs).array() - centring_.x_mm;
    const Eigen::VectorXd qy = xy_mm.col(1).segment(b0, bs).array() - centring_.y_mm;
    auto kb = k_cross.leftCols(bs);
    kernel_.fill_cross(x_, y_, qx, qy, kb);
    f(b0, kb);
  }
}

Eigen::VectorXd ExactGp::mean(const Eigen::MatrixX2d& xy_mm) const {
  check_finite(xy_mm, "query point");
  if (n_ == 0) return Eigen::VectorXd::Constant(xy_mm.rows(), centring_.z_mm);
  const CentredXy q = centre(xy_mm, centring_);
  return kernel_.weighted_sums(x_, y_, weights(), q.x, q.y).array() + centring_.z_mm;
}

Eigen::MatrixXd ExactGp::mean_on_grid(const Eigen::VectorXd& xs_mm, const Eigen::VectorXd& ys_mm) const {
  const Eigen::Index nx = xs_mm.size(), ny = ys_mm.size();
  Eigen::MatrixX2d xs_as_points(nx, 2), ys_as_points(ny, 2);
  xs_as_points << xs_mm, Eigen::VectorXd::Zero(nx);
  ys_as_points << Eigen::VectorXd::Zero(ny), ys_mm;
  check_finite(xs_as_points, "grid x value");
  check_finite(ys_as_points, "grid y value");
  if (n_ == 0 || kernel_kind() != KernelKind::rbf) {
    Eigen::MatrixX2d points(nx * ny, 2);
    for (Eigen::Index i = 0; i < nx; ++i) {
      points.col(0).segment(i * ny, ny).setConstant(xs_mm[i]);
      points.col(1).segment(i * ny, ny) = ys_mm;
    }
    const Eigen::VectorXd flat = mean(points);
    return Eigen::Map<const Eigen::MatrixXd>(flat.data(), ny, nx).transpose();
  }
  // exp(-(dx^2 + dy^2) / 2l^2) = exp(-dx^2 / 2l^2) exp(-dy^2 / 2l^2).
  const double l = kernel_.hyperparameters().lengthscale_mm, c = -0.5 / (l * l);
  // One axis's factor for a centred training coordinate down a column:
  // exp(c (g - centre - coordinate)^2).
  const auto axis_factor = [c](auto column, const Eigen::VectorXd& grid_mm, double centre_mm, double coordinate_mm) {
    column.array() = (grid_mm.array() - centre_mm - coordinate_mm).square() * c;
    exp_in_place(column.array());
  };
  Eigen::MatrixXd ex(nx, n_), ey(ny, n_);
  // The y factors on a second thread while this one solves for the weights
  // (a pass over the whole factor) and makes the x factors.
  std::future<void> y_factors = std::async(std::launch::async, [&] {
    for (Eigen::Index p = 0; p < n_; ++p) axis_factor(ey.col(p), ys_mm, centring_.y_mm, y_[p]);
  });
  const Eigen::VectorXd& alpha = weights();
  for (Eigen::Index p = 0; p < n_; ++p) {
    axis_factor(ex.col(p), xs_mm, centring_.x_mm, x_[p]);
    ex.col(p) *= alpha[p];
  }
  y_factors.get();
  Eigen::MatrixXd out = kernel_.hyperparameters().signal_variance_mm2 * product_transposed(ex, ey);
  out.array() += centring_.z_mm;
  return out;
}

void ExactGp::extend_cached_rows(const Eigen::MatrixX2d& xy_mm) const {
  FactorStore& store = *store_;  // the caller holds store.mutex
  const Eigen::Index m = xy_mm.rows();
  if (store.candidates_mm.rows() != m || store.candidates_mm != xy_mm || store.v.rows() != store.l.rows()) {
    store.candidates_mm = xy_mm;
    store.v.resize(store.l.rows(), m);
    advise_huge_pages(store.v);
    store.v_rows = 0;
    store.v_norms = Eigen::RowVectorXd::Zero(m);
    store.gram.resize(0, 0);
    store.gram_rows = 0;
  }
  const Eigen::Index r = store.v_rows;
  if (r < n_) {
    // New rows: V2 = L22^-1 (K(X2, C) - L21 V1).
    const Eigen::Index k = n_ - r;
    const Eigen::VectorXd qx = xy_mm.col(0).array() - centring_.x_mm;
    const Eigen::VectorXd qy = xy_mm.col(1).array() - centring_.y_mm;
    auto v2 = store.v.middleRows(r, k);
    kernel_.fill_cross(x_.segment(r, k), y_.segment(r, k), qx, qy, v2);
    const Eigen::MatrixXd& l = store.l;
    if (r > 0) subtract_product(v2, l.block(r, 0, k, r), store.v.topRows(r));
    solve_lower_in_place(l.block(r, r, k, k), v2);
    store.v_norms += v2.colwise().squaredNorm();
    store.v_rows = n_;
  }
}

void ExactGp::variance_at_cached(const Eigen::MatrixX2d& xy_mm, Eigen::VectorXd& out) const {
  FactorStore& store = *store_;
  std::lock_guard<std::mutex> lock(store.mutex);
  extend_cached_rows(xy_mm);
  // An older snapshot (fewer rows than the cache holds) sums its own rows.
  if (store.v_rows == n_)
    out -= store.v_norms.transpose();
  else
    out -= store.v.topRows(n_).colwise().squaredNorm().transpose();
}

void ExactGp::covariance_at_cached(const Eigen::MatrixX2d& xy_mm, Eigen::MatrixXd& out) const {
  FactorStore& store = *store_;
  std::lock_guard<std::mutex> lock(store.mutex);
  extend_cached_rows(xy_mm);
  const Eigen::Index m = xy_mm.rows();
  if (store.v_rows != n_) {  // an older snapshot: its own rows
    const auto v = store.v.topRows(n_);
    out.selfadjointView<Eigen::Lower>().rankUpdate(v.transpose(), -1.0);
    return;
  }
  if (store.gram.rows() != m || store.gram_rows > n_) {
    store.gram = Eigen::MatrixXd::Zero(m, m);
    store.gram_rows = 0;
  }
  // The rows added since the last call: a rank-k update of the lower triangle.
  if (store.gram_rows < n_) {
    const auto v2 = store.v.middleRows(store.gram_rows, n_ - store.gram_rows);
    add_row_gram_lower(store.gram, v2);
    store.gram_rows = n_;
  }
  out.triangularView<Eigen::Lower>() -= store.gram;
}

Eigen::VectorXd ExactGp::variance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count) const {
  check_finite(xy_mm, "query point");
  const Eigen::Index m = xy_mm.rows();
  const double prior = kernel_.prior_variance_mm2();
  Eigen::VectorXd out = Eigen::VectorXd::Constant(m, prior);
  std::size_t clamped = 0;
  if (n_ > 0 && m > 0) {
    if (m <= options_.max_cached_candidates) {
      variance_at_cached(xy_mm, out);
    } else {
      for_each_cross_block(xy_mm, [&](Eigen::Index b0, CrossBlock kb) {
        solve_lower_in_place(factor(), kb);
        out.segment(b0, kb.cols()) -= kb.colwise().squaredNorm().transpose();
      });
    }
    clamped = clamp_latent_variance(out, "GP", n_);
  }
  if (clamped_count) *clamped_count = clamped;
  return out;
}

Eigen::MatrixXd ExactGp::covariance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count) const {
  check_finite(xy_mm, "query point");
  const Eigen::Index m = xy_mm.rows();
  Eigen::MatrixXd out(m, m);
  const CentredXy q = centre(xy_mm, centring_);
  kernel_.fill_lower(q.x, q.y, 0.0, out);  // the prior, K(C, C)
  std::size_t clamped = 0;
  if (n_ > 0 && m > 0) {
    if (m <= options_.max_cached_candidates) {
      covariance_at_cached(xy_mm, out);
    } else {
      Eigen::MatrixXd v(n_, m);
      kernel_.fill_cross(x_, y_, q.x, q.y, v);
      solve_lower_in_place(factor(), v);
      out.selfadjointView<Eigen::Lower>().rankUpdate(v.transpose(), -1.0);
    }
  }
  clamped = clamp_latent_covariance(out, "GP", n_);
  if (clamped_count) *clamped_count = clamped;
  return out;
}

Eigen::VectorXd ExactGp::candidate_mean(const Eigen::MatrixX2d& xy_mm) const {
  check_finite(xy_mm, "query point");
  const Eigen::Index m = xy_mm.rows();
  if (n_ == 0 || m == 0 || m > options_.max_cached_candidates) return mean(xy_mm);
  FactorStore& store = *store_;
  std::lock_guard<std::mutex> lock(store.mutex);
  extend_cached_rows(xy_mm);
  // The cache's first n_ rows are this model's V, also for an older snapshot.
  Eigen::VectorXd out = store.v.topRows(n_).transpose() * v_;
  out.array() += centring_.z_mm;
  return out;
}

double ExactGp::log_marginal_likelihood() const {
  if (n_ == 0) return 0.0;
  return -0.5 * v_.squaredNorm() - factor().diagonal().array().log().sum() -
         0.5 * static_cast<double>(n_) * std::log(2.0 * std::numbers::pi);
}

const Eigen::VectorXd& ExactGp::weights() const {
  Weights& w = *weights_;
  std::call_once(w.once, [&] {
    w.alpha = v_;
    solve_lower_transposed_in_place(factor(), w.alpha);
  });
  return w.alpha;
}

Eigen::MatrixXd ExactGp::cholesky_factor() const { return factor().triangularView<Eigen::Lower>(); }

}  // namespace touchcloud::gp
