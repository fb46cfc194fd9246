// Exact Gaussian-process surface z = f(x, y) in mm, at fixed hyperparameters.
// Keeps the Cholesky factor L of A = K + (s^2 + c) I (c: jitter, if needed),
// v = L^-1 (z - z0) and, once the mean is asked for, alpha = A^-1 (z - z0).
// The mean runs through alpha one query at a time (Kernel::weighted_sums);
// the variance through L^-1 k_x in query blocks (memory n x block), only
// where asked. New touches extend L by a bordered Cholesky update instead of
// a refactorisation.
//
// Copies are cheap snapshots: a bordered update only appends rows to L, so a
// copy and the model it came from share one append-only factor store; each
// reads only its own n x n corner, which no later update writes. An update
// from a model that is not the newest on its store (a second branch) copies
// the factor first. The variance at a repeated candidate set (the next-touch
// grid) keeps V = L^-1 K(X, C) in the store and extends it by the new rows
// only: O(k n m) per touch of k points instead of O(n^2 m).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameters.hpp"
#include "touchcloud/gp/jittered_cholesky.hpp"
#include "touchcloud/gp/kernel.hpp"
#include "touchcloud/gp/training_data.hpp"

namespace touchcloud::gp {

struct ExactGpOptions {
  JitterSchedule jitter;
  // The centring's z, the level the mean returns to far from the data, when
  // fit() takes it from the data.
  PriorMean prior_mean = PriorMean::mean;
  // The variance's cross-covariance blocks hold at most this many doubles
  // (n x block queries).
  Eigen::Index query_block_doubles = Eigen::Index{1} << 21;  // 16 MB
  // Room left for later touches when the factor is (re)allocated, as a
  // fraction of the training size; growing copies the whole factor.
  double capacity_slack = 0.25;
  // Candidate sets up to this many points have V = L^-1 K(X, C) cached for the
  // next query of the same set (memory capacity x m doubles).
  Eigen::Index max_cached_candidates = 1024;
  // A bordered update's L21 = K21 L^-T from a left-side solve of its
  // transpose (true) or a right-side one (false); unset: the faster form
  // for the BLAS kernels in use (left_side_solve_preferred). The two agree
  // to rounding.
  std::optional<bool> left_side_update = std::nullopt;
};

enum class UpdatePath { bordered, refactorised };
std::string to_string(UpdatePath path);

struct UpdateReport {
  UpdatePath path = UpdatePath::bordered;
  Eigen::Index points_added = 0;
  CholeskyReport factorisation;  // jitter in force after the update
  std::string reason;            // why a refactorisation was needed; empty otherwise
};

class ExactGp {
 public:
  ExactGp(KernelKind kind, const Hyperparameters& h, ExactGpOptions options = {});

  // Replaces the training set. The centring comes from the data unless given;
  // zero points leave the prior (mean z0, variance = signal variance).
  // InputError on bad input (the model is unchanged); RunError when A cannot
  // be factorised within the jitter schedule (the model is left empty: the
  // prior). add_points behaves the same way.
  void fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm);
  void fit(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm, const Centring& centring);

  // Adds touches at the same hyperparameters and centring (so the result equals
  // fit(all points, same centring) when no jitter is involved). Falls back to a
  // jittered refactorisation when the new Schur complement is not positive.
  UpdateReport add_points(const Eigen::MatrixX2d& xy_mm, const Eigen::VectorXd& z_mm);

  // Makes room for `points` training points without reallocating later.
  void reserve(Eigen::Index points);
  Eigen::Index capacity() const;

  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy_mm) const;
  // Mean on the grid xs x ys: result(i, j) at (xs[i], ys[j]). The RBF kernel
  // factorises over x and y, so this costs (nx + ny) n exponentials and one
  // matrix product instead of nx ny n exponentials; Matern 5/2 does not, and
  // goes through mean().
  Eigen::MatrixXd mean_on_grid(const Eigen::VectorXd& xs_mm, const Eigen::VectorXd& ys_mm) const;
  // Latent (noise-free) variance, mm^2, clamped at 0; the number of clamped
  // values goes to *clamped_count when given; RunError for a value that is not
  // finite (latent_variance.hpp). Thread-safe, like every const member; a
  // set asked for again (same points, same order) reuses V.
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count = nullptr) const;
  // Latent posterior covariance among the query points, m x m: K(C, C) - V^T V
  // with V = L^-1 K(X, C); exactly symmetric, its diagonal clamped and
  // counted as variance()'s, RunError for an entry that is not finite. A set
  // asked for again keeps V^T V and adds the new rows' part only (a rank-k
  // update per touch of k points instead of n m^2).
  Eigen::MatrixXd covariance(const Eigen::MatrixX2d& xy_mm, std::size_t* clamped_count = nullptr) const;
  // Posterior mean at a candidate set from its cached V: mu = z0 + V^T v
  // (k(C, X) A^-1 (z - z0) with A^-1 = L^-T L^-1), 2 n m flops once V is up
  // to date instead of the n^2 solve for the weights and n m exponentials.
  // Equal to mean() up to rounding; mean() itself for a set too large to cache.
  Eigen::VectorXd candidate_mean(const Eigen::MatrixX2d& xy_mm) const;
  double log_marginal_likelihood() const;

  Eigen::Index size() const { return n_; }
  KernelKind kernel_kind() const { return kernel_.kind(); }
  const Hyperparameters& hyperparameters() const { return kernel_.hyperparameters(); }
  const Centring& centring() const { return centring_; }
  const CholeskyReport& factorisation() const { return factorisation_; }
  Eigen::MatrixXd cholesky_factor() const;         // L, n x n, zero above the diagonal
  // alpha = A^-1 (z - z0), solved on the first call after a fit or update (a
  // triangular solve over all of L, n^2 flops reading the whole factor: the
  // next-touch choice does not need it, the mean does). Thread-safe.
  const Eigen::VectorXd& weights() const;

 private:
  struct FactorStore;
  void refactorise();  // from x_, y_, z_ with the jitter schedule, into a fresh store
  Eigen::Index capacity_for(Eigen::Index points) const;
  // Makes this model the only writer of rows [n_, n_ + k) of its store, moving
  // to a copy of the factor when another model writes there or room is short.
  void claim_rows(Eigen::Index k);
  void move_to_new_store(Eigen::Index capacity);
  // The candidate cache (store mutex held): V for `xy_mm` up to row n_.
  void extend_cached_rows(const Eigen::MatrixX2d& xy_mm) const;
  void variance_at_cached(const Eigen::MatrixX2d& xy_mm, Eigen::VectorXd& out) const;
  void covariance_at_cached(const Eigen::MatrixX2d& xy_mm, Eigen::MatrixXd& out) const;
  Eigen::Index query_block() const;
  // Calls f(first query, K(train, block)) over `xy_mm` in blocks of
  // query_block() columns, so memory stays n x block whatever the query count.
  using CrossBlock = Eigen::Block<Eigen::MatrixXd, Eigen::Dynamic, Eigen::Dynamic, true>;
  using CrossBlockFunction = std::function<void(Eigen::Index, CrossBlock)>;
  void for_each_cross_block(const Eigen::MatrixX2d& xy_mm, const CrossBlockFunction& f) const;
  Eigen::Block<Eigen::MatrixXd> factor();
  Eigen::Block<const Eigen::MatrixXd> factor() const;

  Kernel kernel_;
  ExactGpOptions options_;
  Centring centring_;
  bool centring_fixed_ = false;
  Eigen::Index n_ = 0;
  Eigen::VectorXd x_, y_, z_;  // centred
  std::shared_ptr<FactorStore> store_;  // lower n x n corner holds L
  Eigen::VectorXd v_;          // L^-1 (z - z0), kept so updates extend it
  // alpha for this state of the model, solved once when first asked; copies
  // share it until either changes (then it is replaced, never modified).
  struct Weights {
    std::once_flag once;
    Eigen::VectorXd alpha;
  };
  std::shared_ptr<Weights> weights_;
  CholeskyReport factorisation_;
};

}  // namespace touchcloud::gp
