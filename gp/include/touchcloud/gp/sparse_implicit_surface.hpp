// The implicit surface for tens of thousands of training points: the same
// GP on the signed distance as ImplicitSurface (same touches, signed pairs,
// prior sphere, kernels and hyperparameter selection on a strided subset),
// summarised by m inducing points in Titsias' variational form (VFE, as
// SparseVfeGp for the height field):
//   mean(x) = prior(x) + k_xu w,  var(x) = k_xx - |L_uu^-1 k_ux|^2 + |L_B^-1 L_uu^-1 k_ux|^2
// with A = L_uu^-1 K_un / s, B = I + A A^T, w = L_uu^-T B^-1 A r / s.
//
// Why this form and not local experts: a touch changes A by its own columns
// (B by a rank-k update, O(k m^2)) and the inducing set by a few rows, so a
// touch costs O(m^2 (k + m)) whatever n is, one global field stays continuous
// across the whole object (local experts need blending at their borders,
// where a sign error would cut the level set), and the posterior converges
// to the exact one as the inducing set grows.
//
// Inducing points: the touched surface covered greedily by sites at least
// `inducing_spacing_mm` apart, chosen among the contact points that carry a
// signed pair; each site brings its pair (+offset and -offset along the
// normal) as two inducing points. Pairs on both sides are what let the field
// change sign across the surface (kernels centred on the surface alone are
// even about it). A site, once chosen, stays: a touch on new ground adds
// sites by extending L_uu and A by rows. A touch's swept points (the space
// its press came through) farther than the spacing from every site are
// sites of their own, single inducing points: that space can lie far from
// any contact (a cup's mouth over its floor).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/gp/implicit_surface.hpp"

namespace touchcloud::gp {

struct SparseImplicitOptions {
  double inducing_spacing_mm = 8.0;  // least distance between two sites of signed pairs
  void validate() const;             // InputError naming the field
};

class SparseImplicitSurface : public ImplicitTouches {
 public:
  // options.max_training_points is not used here. InputError on invalid options.
  SparseImplicitSurface(ImplicitSurfaceOptions options, SparseImplicitOptions sparse);

  // As ImplicitSurface::add. Paths: selected (hyperparameters selected, the
  // form built from all points), bordered (the touch's columns and any new
  // sites added), refactorised (built again from all points at the same
  // hyperparameters, when extending L_uu loses positive definiteness).
  ImplicitUpdate add(const ImplicitTouch& touch);

  // As ImplicitSurface::mean and ::variance (variance clamped at 0 and
  // counted, RunError when not finite; InputError before the first touch).
  Eigen::VectorXd mean(const Eigen::Ref<const Eigen::MatrixX3d>& query_mm, int threads = 1) const;
  Eigen::VectorXd variance(const Eigen::Ref<const Eigen::MatrixX3d>& query_mm, std::size_t* clamped = nullptr) const;

  Eigen::Index inducing_size() const { return m_; }

 private:
  void add_sites(Eigen::Index from, const ImplicitTouch& touch);  // of the touch at rows [from, ...)
  void rebuild();                                            // L_uu, A, B from all points at h_
  bool extend_inducing(Eigen::Index from);                   // rows [from, m_) of u_; false: rebuild
  void add_columns(Eigen::Index from);                       // training rows [from, n)
  void solve_weights();
  Eigen::VectorXd residuals(Eigen::Index first, Eigen::Index count) const;  // signed distance minus prior
  void require_touches() const;

  SparseImplicitOptions sparse_;
  std::vector<Eigen::Vector3d> sites_;
  Eigen::MatrixX3d u_{0, 3};  // inducing points, rows [0, m_)
  Eigen::Index m_ = 0;
  Eigen::Index columns_ = 0;  // training points in A, B and az_
  double jitter_mm2_ = 0;     // on K_uu's diagonal
  Eigen::MatrixXd l_uu_;      // lower m_ x m_ corner
  Eigen::MatrixXd a_;         // m_ x columns_ corner: L_uu^-1 K_un / s
  Eigen::MatrixXd b_;         // lower m_ x m_ corner: I + A A^T
  Eigen::VectorXd az_;        // A r / s (r: signed distance minus prior)
  Eigen::MatrixXd l_b_;       // chol(B)
  Eigen::VectorXd weights_;   // w above
  Eigen::MatrixXd variance_form_;  // lower: K_uu^-1 - (L_uu B L_uu^T)^-1, strict part doubled
};

}  // namespace touchcloud::gp
