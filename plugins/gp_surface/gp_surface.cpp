// gp_surface: the Gaussian-process surface z = f(x, y) over every touch so
// far, fitted by the gp library's SurfaceFit (touchcloud/gp/surface_fit.hpp):
// new touches extend the Cholesky factor (a bordered update); the
// hyperparameters are selected again only when the training set has grown by
// `reselect_growth` since the last selection, on a subset of at most
// `selection_points` points made of `selection_runs` runs of consecutive
// points spread over the data (then one fit on all).
//
// method: sparse fits a VFE sparse GP afresh each touch on inducing points, a
// farthest-point subset of the touches whose first point is drawn with the
// stage's rng. The parameters are the fit's options; its summary gives the
// metrics and the values used.
#include "touchcloud/gp/factor_algebra.hpp"
#include "touchcloud/gp/surface_fit.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class GpSurface final : public Stage {
  gp::SurfaceFitOptions options_;
  std::optional<gp::SurfaceFit> fit_;

  void declare_parameters(ParameterSet& p) override {
    p.add("kernel", options_.kernel, gp::KernelKind::rbf, {{"rbf", gp::KernelKind::rbf}, {"matern52", gp::KernelKind::matern52}})
        .doc("covariance function");
    p.add("method", options_.method, gp::FitMethod::exact, {{"exact", gp::FitMethod::exact}, {"sparse", gp::FitMethod::sparse}})
        .doc("exact GP, or the sparse VFE approximation on inducing points");
    p.add("inducing_points", options_.inducing_points, 500).at_least(1).unit("points")
        .doc("method sparse: inducing points, a farthest-point subset of the touches (all when fewer)");
    p.add("selection_points", options_.selection_points, 0).at_least(0).unit("points")
        .doc("select hyperparameters on a subset of at most this many points, then fit all "
             "(0: all; method sparse: inducing_points)");
    p.add("selection_runs", options_.selection_runs, 8).at_least(1)
        .doc("the subset is this many runs of consecutive points (parts of touches), spread evenly over the data");
    p.add("reselect_growth", options_.reselect_growth, 0.5).at_least(0.0)
        .doc("select hyperparameters again once the points have grown by this fraction (0: every touch)");
    p.add("screening_points", options_.screening_points, 500).at_least(0)
        .doc("restarts of the model selection run on a subset of this size (0: all points)");
    p.add("initial_lengthscale_mm", options_.initial_lengthscale_mm, 10.0).unit("mm").above(0.0)
        .doc("lengthscale while there are too few points to select one");
    p.add("max_noise_mm", options_.max_noise_mm, 1.0).unit("mm").above(0.0)
        .doc("largest noise standard deviation model selection may choose (touch points are accurate to a few "
             "tenths of a mm); keeps few or rough points from being explained as noise around a flat mean");
    p.add("min_noise_mm", options_.min_noise_mm, 0.0).unit("mm").at_least(0.0)
        .doc("smallest noise standard deviation model selection may choose (0: no floor): a sensor's "
             "repeatability between touches; keeps a rough kernel from passing exactly through neighbouring points "
             "of two touches that disagree, and swinging far off between them");
    p.add("prior_mean", options_.prior_mean, gp::PriorMean::mean, {{"mean", gp::PriorMean::mean}, {"median", gp::PriorMean::median}})
        .doc("the level the surface returns to far from the touches: the touched points' mean, or their median "
             "(method exact; a relief on a plate: the plate, where most touches land, so ground beside a tall part "
             "that no touch reached is not drawn at the mean height)");
    p.add("max_lengthscale_mm", options_.max_lengthscale_mm).unit("mm").above(0.0)
        .doc("largest lengthscale model selection may choose; not set: no cap (a long lengthscale carries a steep "
             "wall's slope past its foot, into ground no touch reached)");
    p.add("blas_threads", options_.blas_threads).at_least(1).unit("threads").needs("OpenBLAS", gp::factor_algebra_threads_settable())
        .doc("threads of the factorisations and solves (OpenBLAS: one count for the whole process); not set: "
             "OpenBLAS's own, a thread per core; 1 leaves the other cores to background stages");
  }
  // The rules between the options (min_noise_mm below max_noise_mm, ...) are
  // the fit's own.
  void on_check(RunContext&) override {
    if (const auto problem = options_.problem()) throw ParameterError(problem->field, problem->detail);
  }
  void on_configure(RunContext& ctx) override {
    fit_.emplace(options_);
    const gp::SurfaceFitSummary& used = fit_->summary();
    ctx.used("blas_threads", static_cast<std::int64_t>(used.blas_threads));
    ctx.used("dense_algebra", used.dense_algebra);
    ctx.used("kernel_exp", used.kernel_exp);
    if (used.matern_mean_sums) ctx.used("matern_mean_sums", *used.matern_mean_sums);
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

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& cloud = io.input<CloudConstPtr>("cloud");
    if (!cloud) throw RunError("no cloud to add");
    const Eigen::Index k = static_cast<Eigen::Index>(cloud->size());
    Eigen::MatrixX2d xy(k, 2);
    Eigen::VectorXd z(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const auto& p = (*cloud)[static_cast<std::size_t>(i)];
      xy.row(i) << p.x, p.y;
      z[i] = p.z;
    }
    const SurfaceModelPtr surface = fit_->add(xy, z, ctx.rng());
    const gp::TouchSummary& touch = fit_->summary().touches.back();
    if (const auto& s = touch.selection) {
      ctx.metric("lml", s->lml);
      ctx.metric("selection_points", static_cast<double>(s->points), "points");
      ctx.metric("selection_evaluations", s->evaluations);
      ctx.metric("selection_s", s->seconds, "s");
    }
    if (!touch.refactorised_because.empty()) ctx.log("refactorised: " + touch.refactorised_because);
    if (touch.inducing_points) {
      ctx.metric("inducing_points", static_cast<double>(*touch.inducing_points), "points");
      ctx.metric("vfe_bound", *touch.vfe_bound);
    }
    if (touch.jitter_mm2) ctx.metric("jitter_mm2", *touch.jitter_mm2, "mm^2");
    ctx.metric("training_points", static_cast<double>(touch.training_points), "points");
    ctx.metric("update_path", static_cast<double>(touch.path));
    ctx.metric("lengthscale_mm", touch.hyperparameters.lengthscale_mm, "mm");
    ctx.metric("signal_variance_mm2", touch.hyperparameters.signal_variance_mm2, "mm^2");
    ctx.metric("noise_variance_mm2", touch.hyperparameters.noise_variance_mm2, "mm^2");
    io.output("surface", surface);
  }

  void on_finish(RunContext& ctx) override {
    ctx.metric("selections", fit_->summary().selections);
    ctx.note("update_path", "per touch: 0 unchanged, 1 bordered Cholesky update, 2 refactorised with jitter, "
                            "3 hyperparameters selected and refitted (method sparse: refitted every touch)");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::GpSurface, "gp_surface", reconstruction, "Fits a Gaussian-process surface z = f(x, y) to the touches")
