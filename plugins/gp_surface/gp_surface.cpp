// gp_surface: the Gaussian-process surface z = f(x, y) over every touch so
// far. New touches extend the Cholesky factor (a bordered update); the
// hyperparameters are selected again, warm-started, only when the training
// set has grown by `reselect_growth` since the last selection.
#include "gp/hyperparameter_search.hpp"
#include "gp_surface_model.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud {

class GpSurface final : public Stage {
  std::string kernel_;
  double reselect_growth_ = 0.5;
  int screening_points_ = 500;
  double initial_lengthscale_mm_ = 10.0;

  Eigen::MatrixX2d xy_{0, 2};
  Eigen::VectorXd z_;
  std::shared_ptr<const gp::ExactGp> gp_;
  Eigen::Index selected_at_ = 0;  // training size at the last selection (0: none yet)
  gp::Hyperparameters last_;
  int selections_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("kernel", kernel_, std::string("rbf")).choices({"rbf", "matern52"}).doc("covariance function");
    p.add("reselect_growth", reselect_growth_, 0.5).at_least(0.0)
        .doc("select hyperparameters again once the points have grown by this fraction (0: every touch)");
    p.add("screening_points", screening_points_, 500).at_least(0)
        .doc("restarts of the model selection run on a subset of this size (0: all points)");
    p.add("initial_lengthscale_mm", initial_lengthscale_mm_, 10.0).unit("mm").above(0.0)
        .doc("lengthscale while there are too few points to select one");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<CloudConstPtr>("cloud", "the points this touch adds, base frame, mm");
    ports.output<SurfaceModelPtr>("surface", "the fitted surface");
  }

  void append(const PointCloud& cloud) {
    const Eigen::Index n0 = xy_.rows(), k = static_cast<Eigen::Index>(cloud.size());
    xy_.conservativeResize(n0 + k, 2);
    z_.conservativeResize(n0 + k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const auto& p = cloud[static_cast<std::size_t>(i)];
      xy_.row(n0 + i) << p.x, p.y;
      z_[n0 + i] = p.z;
    }
  }

  // A fresh model at hyperparameters chosen for all the points.
  void select(RunContext& ctx) {
    gp::SearchOptions options;
    options.kernel = gp::kernel_kind_from_string(kernel_);
    options.screening_points = screening_points_;
    if (selected_at_ > 0) options.start_hyperparameters = {last_};
    const gp::SearchResult r = gp::select_hyperparameters(xy_, z_, options);
    auto model = std::make_shared<gp::ExactGp>(options.kernel, r.hyperparameters);
    model->fit(xy_, z_);
    gp_ = model;
    last_ = r.hyperparameters;
    selected_at_ = xy_.rows();
    ++selections_;
    ctx.metric("lml", r.lml);
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& cloud = io.input<CloudConstPtr>("cloud");
    if (!cloud) throw RunError("no cloud to add");
    const Eigen::Index n0 = xy_.rows();
    append(*cloud);
    const Eigen::Index n = xy_.rows();
    constexpr Eigen::Index kMinSelectionPoints = 3;
    double path = 0;  // 0 unchanged, 1 bordered update, 2 refactorised, 3 hyperparameters selected
    if (n < kMinSelectionPoints) {
      // Too few points to select hyperparameters: a GP at set values.
      gp::Hyperparameters h;
      h.lengthscale_mm = initial_lengthscale_mm_;
      h.noise_variance_mm2 = 0.01;
      auto model = std::make_shared<gp::ExactGp>(gp::kernel_kind_from_string(kernel_), h);
      model->fit(xy_, z_);
      gp_ = model;
    } else if (selected_at_ == 0 || static_cast<double>(n) >= (1.0 + reselect_growth_) * static_cast<double>(selected_at_)) {
      select(ctx);
      path = 3;
    } else if (n > n0) {
      auto model = std::make_shared<gp::ExactGp>(*gp_);  // the previous output stays as it was
      const gp::UpdateReport report = model->add_points(xy_.bottomRows(n - n0), z_.tail(n - n0));
      path = report.path == gp::UpdatePath::bordered ? 1 : 2;
      if (!report.reason.empty()) ctx.log("refactorised: " + report.reason);
      gp_ = model;
    }
    const auto& h = gp_->hyperparameters();
    ctx.metric("training_points", static_cast<double>(n), "points");
    ctx.metric("update_path", path);
    ctx.metric("lengthscale_mm", h.lengthscale_mm, "mm");
    ctx.metric("signal_variance_mm2", h.signal_variance_mm2, "mm^2");
    ctx.metric("noise_variance_mm2", h.noise_variance_mm2, "mm^2");
    ctx.metric("jitter_mm2", gp_->factorisation().jitter_mm2, "mm^2");
    io.output("surface", SurfaceModelPtr(std::make_shared<GpSurfaceModel>(gp_)));
  }

  void on_finish(RunContext& ctx) override {
    ctx.metric("selections", selections_);
    ctx.note("update_path", "per touch: 0 unchanged, 1 bordered Cholesky update, 2 refactorised with jitter, "
                            "3 hyperparameters selected and refitted");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::GpSurface, "gp_surface", "Fits a Gaussian-process surface z = f(x, y) to the touches")
