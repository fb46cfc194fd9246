// gp_surface: the Gaussian-process surface z = f(x, y) over every touch so
// far. New touches extend the Cholesky factor (a bordered update); the
// hyperparameters are selected again only when the training set has grown by
// `reselect_growth` since the last selection, on a subset of at most
// `selection_points` points made of `selection_runs` runs of consecutive
// points spread over the data (then one fit on all). Each selection after the
// first is warm-started from the last optimum and its curvature: a few
// quasi-Newton steps, and a single gradient when the optimum has not moved.
//
// method: sparse fits a VFE sparse GP (gp/sparse_vfe.hpp) afresh each touch,
// O(n m^2), on m inducing points: a farthest-point subset of the touches
// (gp/inducing_points.hpp) whose first point is drawn with the stage's rng;
// all the points when m >= n, which is then the exact GP. Its
// hyperparameters are selected with the exact LML on such a subset of at most
// `inducing_points` points (the VFE bound has no gradient here yet).
#include <chrono>
#include <random>

#include "gp/factor_algebra.hpp"
#include "gp/hyperparameter_search.hpp"
#include "gp/inducing_points.hpp"
#include "gp/point_subset.hpp"
#include "gp/simd_path.hpp"
#include "gp/training_data.hpp"
#include "gp/vector_exp.hpp"
#include "gp_surface_model.hpp"
#include "sparse_surface_model.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class GpSurface final : public Stage {
  enum class Method { Exact, Sparse };
  gp_surface::KernelKind kernel_ = gp_surface::KernelKind::rbf;
  Method method_ = Method::Exact;
  int inducing_points_ = 500;
  int selection_points_ = 0;
  int selection_runs_ = 8;
  double reselect_growth_ = 0.5;
  int screening_points_ = 500;
  double initial_lengthscale_mm_ = 10.0;
  double max_noise_mm_ = 1.0;
  double min_noise_mm_ = 0.0;
  std::optional<int> blas_threads_;

  Eigen::MatrixX2d xy_{0, 2};
  Eigen::VectorXd z_;
  std::shared_ptr<const gp_surface::ExactGp> gp_;  // method exact
  SurfaceModelPtr sparse_;                  // method sparse: the last fit
  std::shared_ptr<const gp_surface::GpSurfaceModel> exact_surface_;  // method exact: the last output
  Eigen::Index selected_at_ = 0;  // training size at the last selection (0: none yet)
  gp_surface::Hyperparameters last_;
  Eigen::Matrix2d last_curvature_ = Eigen::Matrix2d::Zero();  // its hessian_per_point, for the next warm start
  int selections_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("kernel", kernel_, gp_surface::KernelKind::rbf, {{"rbf", gp_surface::KernelKind::rbf}, {"matern52", gp_surface::KernelKind::matern52}})
        .doc("covariance function");
    p.add("method", method_, Method::Exact, {{"exact", Method::Exact}, {"sparse", Method::Sparse}})
        .doc("exact GP, or the sparse VFE approximation on inducing points");
    p.add("inducing_points", inducing_points_, 500).at_least(1).unit("points")
        .doc("method sparse: inducing points, a farthest-point subset of the touches (all when fewer)");
    p.add("selection_points", selection_points_, 0).at_least(0).unit("points")
        .doc("select hyperparameters on a subset of at most this many points, then fit all "
             "(0: all; method sparse: inducing_points)");
    p.add("selection_runs", selection_runs_, 8).at_least(1)
        .doc("the subset is this many runs of consecutive points (parts of touches), spread evenly over the data");
    p.add("reselect_growth", reselect_growth_, 0.5).at_least(0.0)
        .doc("select hyperparameters again once the points have grown by this fraction (0: every touch)");
    p.add("screening_points", screening_points_, 500).at_least(0)
        .doc("restarts of the model selection run on a subset of this size (0: all points)");
    p.add("initial_lengthscale_mm", initial_lengthscale_mm_, 10.0).unit("mm").above(0.0)
        .doc("lengthscale while there are too few points to select one");
    p.add("max_noise_mm", max_noise_mm_, 1.0).unit("mm").above(0.0)
        .doc("largest noise standard deviation model selection may choose (touch points are accurate to a few "
             "tenths of a mm); keeps few or rough points from being explained as noise around a flat mean");
    p.add("min_noise_mm", min_noise_mm_, 0.0).unit("mm").at_least(0.0)
        .doc("smallest noise standard deviation model selection may choose (0: no floor): a sensor's "
             "repeatability between touches; keeps a rough kernel from passing exactly through neighbouring points "
             "of two touches that disagree, and swinging far off between them");
    p.add("blas_threads", blas_threads_).at_least(1).unit("threads").needs("OpenBLAS", gp_surface::factor_algebra_threads_settable())
        .doc("threads of the factorisations and solves (OpenBLAS: one count for the whole process); not set: "
             "OpenBLAS's own, a thread per core; 1 leaves the other cores to background stages");
  }
  void on_check(RunContext&) override {
    if (min_noise_mm_ >= max_noise_mm_)
      throw ParameterError("min_noise_mm", "must be below max_noise_mm (" + number_text(max_noise_mm_) + " mm)");
  }
  void on_configure(RunContext& ctx) override {
    gp_surface::set_factor_algebra_threads(blas_threads_.value_or(0));
    ctx.used("blas_threads", static_cast<std::int64_t>(gp_surface::factor_algebra_threads()));
    ctx.used("dense_algebra", std::string(gp_surface::factor_algebra_backend()));
    ctx.used("kernel_exp", std::string(gp_surface::vector_exp_path()));
    if (kernel_ == gp_surface::KernelKind::matern52) {
      const gp_surface::SimdPath sums = gp_surface::fastest_simd_path();
      ctx.used("matern_mean_sums",
               sums == gp_surface::SimdPath::none ? std::string("kernel columns (Eigen)")
                                                  : std::string(gp_surface::to_string(sums)) + " (inline exp)");
    }
  }
  void declare_ports(PortSet& ports) override {
    ports.input<CloudConstPtr>("cloud", "the points this touch adds, base frame, mm");
    ports.output<SurfaceModelPtr>("surface", "the fitted surface");
    ports.metric("lml", "", "log marginal likelihood at the selected hyperparameters (at each selection)")
        .higher_is_better();
    ports.metric("selection_points", "points", "points the hyperparameters were selected on (at each selection)");
    ports.metric("selection_evaluations", "", "likelihood evaluations of the selection (at each selection)");
    ports.metric("selection_s", "s", "time the selection took (at each selection)");
    ports.metric("inducing_points", "points", "method sparse: inducing points of the fit");
    ports.metric("vfe_bound", "", "method sparse: the variational free energy bound of the fit").higher_is_better();
    ports.metric("jitter_mm2", "mm^2", "method exact: jitter added to the kernel matrix's diagonal to factorise it");
    ports.metric("training_points", "points", "points the surface is fitted to");
    ports.metric("update_path", "", "how the fit was updated: 0 unchanged, 1 bordered Cholesky update, 2 refactorised, "
                 "3 hyperparameters selected");
    ports.metric("lengthscale_mm", "mm", "kernel lengthscale");
    ports.metric("signal_variance_mm2", "mm^2", "kernel signal variance");
    ports.metric("noise_variance_mm2", "mm^2", "noise variance");
    ports.metric("selections", "", "hyperparameter selections over the run").final();
  }

  // The touch is checked before it joins the training set: a non-finite
  // point would stay there and fail every later fit, so a bad touch is
  // refused whole and the touches so far stay as they were.
  void append(const PointCloud& cloud) {
    const Eigen::Index k = static_cast<Eigen::Index>(cloud.size());
    Eigen::MatrixX2d xy(k, 2);
    Eigen::VectorXd z(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const auto& p = cloud[static_cast<std::size_t>(i)];
      xy.row(i) << p.x, p.y;
      z[i] = p.z;
    }
    gp_surface::check_training(xy, z, "point of this touch");
    const Eigen::Index n0 = xy_.rows();
    xy_.conservativeResize(n0 + k, 2);
    z_.conservativeResize(n0 + k);
    xy_.bottomRows(k) = xy;
    z_.tail(k) = z;
  }

  // Hyperparameters for all the points, from a subset when asked; warm-started
  // (with the last selection's curvature) after the first.
  void select(RunContext& ctx) {
    gp_surface::SearchOptions options;
    options.kernel = kernel_;
    options.screening_points = screening_points_;
    options.bounds.noise_sd_max = max_noise_mm_;
    options.bounds.noise_sd_min = min_noise_mm_;
    options.stop_gain = 1e-6;  // hyperparameters to ~0.1 %: the surface cannot tell them apart
    if (selected_at_ > 0) {
      options.start_hyperparameters = {last_};
      options.start_hessian_per_point = last_curvature_;
    }
    const auto started = std::chrono::steady_clock::now();
    const Eigen::Index n = xy_.rows();
    const Eigen::Index limit = selection_points_ > 0 ? selection_points_ : (method_ == Method::Sparse ? inducing_points_ : n);
    // Runs of consecutive points (parts of single touches) spread evenly
    // over the data keep the touches' point density (gp/point_subset.hpp).
    const auto [sub_xy, sub_z] = gp_surface::subset_of_runs(xy_, z_, limit, selection_runs_);
    const gp_surface::SearchResult r = gp_surface::select_hyperparameters(sub_xy, sub_z, options);
    last_ = r.hyperparameters;
    last_curvature_ = r.hessian_per_point;
    selected_at_ = n;
    ++selections_;
    ctx.metric("lml", r.lml);
    ctx.metric("selection_points", static_cast<double>(std::min(limit, n)), "points");
    int evaluations = r.evaluations;
    for (const gp_surface::StartReport& start : r.screening) evaluations += start.evaluations;
    for (const gp_surface::StartReport& level : r.refinement) evaluations += level.evaluations;
    ctx.metric("selection_evaluations", evaluations);
    ctx.metric("selection_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), "s");
  }

  std::optional<std::array<double, 2>> data_z_range() const {
    if (z_.size() == 0) return std::nullopt;
    return std::array<double, 2>{z_.minCoeff(), z_.maxCoeff()};
  }

  void fit_exact(const gp_surface::Hyperparameters& h) {
    auto model = std::make_shared<gp_surface::ExactGp>(kernel_, h);
    model->fit(xy_, z_);
    gp_ = model;
  }

  SurfaceModelPtr fit_sparse(const gp_surface::Hyperparameters& h, RunContext& ctx) {
    const Eigen::Index n = xy_.rows();
    const Eigen::Index first = std::uniform_int_distribution<Eigen::Index>(0, n - 1)(ctx.rng());
    const std::vector<Eigen::Index> rows = gp_surface::farthest_point_subset(xy_, inducing_points_, first);
    Eigen::MatrixX2d inducing(static_cast<Eigen::Index>(rows.size()), 2);
    for (std::size_t i = 0; i < rows.size(); ++i) inducing.row(static_cast<Eigen::Index>(i)) = xy_.row(rows[i]);
    auto model = std::make_shared<gp_surface::SparseVfeGp>(kernel_, h);
    model->fit(xy_, z_, inducing);
    ctx.metric("inducing_points", static_cast<double>(inducing.rows()), "points");
    ctx.metric("vfe_bound", model->log_marginal_likelihood_bound());
    return std::make_shared<gp_surface::SparseSurfaceModel>(model, data_z_range());
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& cloud = io.input<CloudConstPtr>("cloud");
    if (!cloud) throw RunError("no cloud to add");
    const Eigen::Index n0 = xy_.rows();
    append(*cloud);
    const Eigen::Index n = xy_.rows();
    constexpr Eigen::Index kMinSelectionPoints = 3;
    double path = 0;  // 0 unchanged, 1 bordered update, 2 refactorised, 3 hyperparameters selected
    gp_surface::Hyperparameters h = last_;
    if (n < kMinSelectionPoints) {
      // Too few points to select hyperparameters: a GP at set values.
      h = {};
      h.lengthscale_mm = initial_lengthscale_mm_;
      h.noise_variance_mm2 = 0.01;
      fit_exact(h);  // method sparse too: with no point there is nothing to choose inducing points from
    } else if (selected_at_ == 0 || static_cast<double>(n) >= (1.0 + reselect_growth_) * static_cast<double>(selected_at_)) {
      select(ctx);
      h = last_;
      if (method_ == Method::Exact) fit_exact(h);
      path = 3;
    } else if (method_ == Method::Exact && n > n0) {
      auto model = std::make_shared<gp_surface::ExactGp>(*gp_);  // shares the factor; the previous output stays as it was
      const gp_surface::UpdateReport report = model->add_points(xy_.bottomRows(n - n0), z_.tail(n - n0));
      path = report.path == gp_surface::UpdatePath::bordered ? 1 : 2;
      if (!report.reason.empty()) ctx.log("refactorised: " + report.reason);
      gp_ = model;
    }
    SurfaceModelPtr surface;
    if (method_ == Method::Sparse && n > 0) {
      if (n > n0 || !sparse_) sparse_ = fit_sparse(h, ctx);
      surface = sparse_;
    } else {
      h = gp_->hyperparameters();
      ctx.metric("jitter_mm2", gp_->factorisation().jitter_mm2, "mm^2");
      // An unchanged fit goes out as the same model, which later stages may
      // recognise and not evaluate again.
      if (!exact_surface_ || exact_surface_->gp() != gp_) exact_surface_ = std::make_shared<gp_surface::GpSurfaceModel>(gp_, data_z_range());
      surface = exact_surface_;
    }
    ctx.metric("training_points", static_cast<double>(n), "points");
    ctx.metric("update_path", path);
    ctx.metric("lengthscale_mm", h.lengthscale_mm, "mm");
    ctx.metric("signal_variance_mm2", h.signal_variance_mm2, "mm^2");
    ctx.metric("noise_variance_mm2", h.noise_variance_mm2, "mm^2");
    io.output("surface", surface);
  }

  void on_finish(RunContext& ctx) override {
    ctx.metric("selections", selections_);
    ctx.note("update_path", "per touch: 0 unchanged, 1 bordered Cholesky update, 2 refactorised with jitter, "
                            "3 hyperparameters selected and refitted (method sparse: refitted every touch)");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::GpSurface, "gp_surface", reconstruction, "Fits a Gaussian-process surface z = f(x, y) to the touches")
