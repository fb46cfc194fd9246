// An implicit surface from touches: a GP on the signed distance f(p), p in
// the base frame (mm), f < 0 inside the object, 0 on its surface, > 0
// outside. Each touch gives its contact points (f = 0) and, along the
// outward normal there (the palm's normal), signed points `offset_mm`
// outside (f = +offset) and inside (f = -offset) at every `offset_stride`-th
// point. The prior mean is a sphere around the touched points (f = |p - c| -
// r0, c their centroid and r0 their mean distance from it, fixed at each
// hyperparameter selection), so the zero level set is closed and far from
// the data the model says "outside".
//
// A touch without normals takes its patch's plane normal, turned away from
// the centroid of all points touched (right for shapes convex about it);
// that needs the patch to span a plane and all the points to span space:
// otherwise the side of the surface is unknown and the touch is refused.
//
// Hyperparameters (signal variance, scale, noise) maximise the exact log
// marginal likelihood (gp's L-BFGS search, maximise_lml) on an evenly
// strided subset of at most `selection_points` training points; they are
// selected again once the training set has grown by `reselect_growth` since
// the last selection, and (thin_plate) whenever a touch reaches beyond the
// kernel's R. Between selections a touch extends the Cholesky factor (a
// bordered update), as the height-field GP does.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameters.hpp"
#include "touchcloud/gp/implicit_kernel.hpp"
#include "touchcloud/gp/jittered_cholesky.hpp"

namespace touchcloud::gp {

struct ImplicitTouch {
  Eigen::MatrixX3d points_mm;  // on the surface, base frame
  // Outward unit normal at each point (or none: no rows, see above).
  Eigen::MatrixX3d normals = Eigen::MatrixX3d(0, 3);
  // Points the press's approach swept through before contact, outside the
  // object, each with its signed distance (> 0; none: no rows;
  // add_swept_approach).
  // They open what the smooth field closes across space a gel went through:
  // a cup's mouth over its floor.
  Eigen::MatrixX3d free_mm = Eigen::MatrixX3d(0, 3);
  Eigen::VectorXd free_distance_mm = Eigen::VectorXd(0);
};

// Adds to `touch` the points a press swept: from `contact_mm` back out along
// `outward` (unit), every step_mm up to length_mm, each at its distance s
// from the contact. The object's true distance there lies between the gel's
// half-width (nothing came nearer the axis the gel went down) and s (the
// contact is that far); s is what a face's distance grows as, so the field
// keeps its slope away from the surface (capped at the half-width, the
// field flattened beside the inner wall of a cup and grew sheets there).
void add_swept_approach(ImplicitTouch& touch, const Eigen::Vector3d& contact_mm, const Eigen::Vector3d& outward,
                        double length_mm, double step_mm);

struct ImplicitSurfaceOptions {
  ImplicitKernelKind kernel = ImplicitKernelKind::thin_plate;
  double offset_mm = 2.0;
  int offset_stride = 4;
  Eigen::Index selection_points = 400;
  double reselect_growth = 0.5;
  double max_noise_mm = 0.5;   // noise standard deviation the selection may choose, at most
  double min_noise_mm = 0.01;  // and at least (keeps repeated touches factorisable)
  int max_iterations = 40;     // L-BFGS iterations of a selection
  // The exact form refuses a touch that would take it beyond this many
  // training points (its update and prediction grow as n^2, its selection n^3).
  std::optional<Eigen::Index> max_training_points;
  JitterSchedule jitter;
  void validate() const;  // InputError naming the field, its value and the rule
};

enum class ImplicitUpdatePath { selected, bordered, refactorised };
std::string to_string(ImplicitUpdatePath path);

struct ImplicitUpdate {
  ImplicitUpdatePath path = ImplicitUpdatePath::selected;
  Eigen::Index points_added = 0;      // training points (contact and signed)
  Eigen::Index training_points = 0;   // after the touch
  std::optional<double> lml;          // at a selection, on its subset
  Eigen::Index selection_points = 0;  // the subset's size, at a selection
  double jitter_mm2 = 0;              // added to the diagonal to factorise
  // thin_plate: R's lower bound in diameters of the data, raised from 1 by
  // 1.5 at a time when the covariance was not positive definite (below).
  double scale_floor = 1;
  bool normals_estimated = false;     // the touch came without normals
};

// The training set both forms fit: contact points (f = 0) and signed points.
struct ImplicitTraining {
  Eigen::MatrixX3d x;  // training points, rows [0, n) in use
  Eigen::VectorXd f;   // their signed distances
  Eigen::MatrixX3d contacts{0, 3};
  Eigen::Index n = 0;
  double diameter_mm() const;  // of the training points' bounding box
};

// A touch's outward normals: checked, or estimated when it has none (see the
// top); InputError naming `where` for a touch refused, its swept points
// checked too. `contacts`: the points touched before.
Eigen::MatrixX3d checked_touch_normals(const ImplicitTouch& touch, const Eigen::MatrixX3d& contacts,
                                       const std::string& where, bool& estimated);
// Training points a touch adds (its contact points, their signed pairs, its swept points).
Eigen::Index implicit_rows_of(const ImplicitTouch& touch, const ImplicitSurfaceOptions& options);
// Appends the touch's contact points, their signed pairs, then its swept points.
void append_implicit_training(const ImplicitTouch& touch, const Eigen::MatrixX3d& normals,
                              const ImplicitSurfaceOptions& options, ImplicitTraining& training);

// What both forms keep of their touches and do alike: the options, the
// training set, the prior sphere, and the hyperparameters with the training
// size they were selected at.
class ImplicitTouches {
 public:
  Eigen::Index training_size() const { return data_.n; }
  const Eigen::MatrixX3d& contact_points() const { return data_.contacts; }
  std::size_t touches() const { return touches_; }
  const Hyperparameters& hyperparameters() const { return h_; }
  const ImplicitSurfaceOptions& options() const { return options_; }
  Eigen::Vector3d prior_centre_mm() const { return centre_; }
  double prior_radius_mm() const { return radius_; }

 protected:
  explicit ImplicitTouches(ImplicitSurfaceOptions options);  // InputError on invalid options
  double prior(const Eigen::Vector3d& p) const { return (p - centre_).norm() - radius_; }
  // Whether the touch just appended selects hyperparameters again: the
  // first, the data grown by reselect_growth since the last selection, or
  // (thin_plate) R no longer spanning scale_floor_ times the data, as its
  // kernel asks.
  bool selects_again() const;
  // The thin-plate kernel is only conditionally positive definite: with
  // touches spread all round an object and R near the data's diameter its
  // covariance can have negative eigenvalues beyond any jitter (a few 1e-3
  // of its diagonal for points filling a ball), while at 1.5 diameters and
  // more it is positive definite. Raises scale_floor_ by 1.5 (true), or
  // false for another kernel or once R's floor has been raised three times.
  bool widen_thin_plate();
  // The prior sphere from the contacts, then the hyperparameters (h_,
  // selected_at_) on a subset of the training points of `subset_size`
  // points; returns the subset's log marginal likelihood.
  double select_on_touches(Eigen::Index& subset_size);

  ImplicitSurfaceOptions options_;
  Hyperparameters h_;
  ImplicitTraining data_;
  std::size_t touches_ = 0;
  Eigen::Index selected_at_ = 0;
  double scale_floor_ = 1;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  double radius_ = 0;
};

class ImplicitSurface : public ImplicitTouches {
 public:
  explicit ImplicitSurface(ImplicitSurfaceOptions options = {});  // InputError on invalid options

  // Adds one touch. InputError (the model unchanged) for a touch beyond
  // max_training_points, without
  // points, with a value that is not finite, normals that are not unit
  // length or not one per point, or no normals where the side cannot be told
  // (see the top). RunError when the covariance cannot be factorised.
  ImplicitUpdate add(const ImplicitTouch& touch);

  // Signed distance estimate at each row (mm), and its latent variance (mm^2,
  // finite and >= 0: rounding below 0 is clamped and counted in *clamped,
  // anything not finite a RunError). InputError before the first touch.
  // The mean runs on `threads` threads (0: every hardware thread) with the
  // same result for any count.
  Eigen::VectorXd mean(const Eigen::Ref<const Eigen::MatrixX3d>& query_mm, int threads = 1) const;
  Eigen::VectorXd variance(const Eigen::Ref<const Eigen::MatrixX3d>& query_mm, std::size_t* clamped = nullptr) const;

 private:
  void refactorise();           // L from all training points at h_, with the jitter schedule
  // refactorise(): true, or false with R's floor raised (widen_thin_plate);
  // the RunError when the floor cannot be raised.
  bool factorised();
  void select_and_factorise(ImplicitUpdate& update);  // selects until the covariance factorises
  bool extend_factor(Eigen::Index from);  // bordered update for rows [from, n_); false: not positive
  void solve_weights();
  void require_touches() const;

  Eigen::MatrixXd factor_;  // lower n_ x n_ corner: L L^T = K + (noise + jitter) I
  double jitter_mm2_ = 0;
  Eigen::VectorXd v_;       // L^-1 (f - prior)
  Eigen::VectorXd alpha_;   // L^-T v
};

}  // namespace touchcloud::gp
