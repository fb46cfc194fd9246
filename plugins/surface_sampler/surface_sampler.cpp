// surface_sampler: the fitted surface's mean on a regular lattice over the
// workspace (the paper evaluates 200 x 200), as a cloud for scoring and
// writing. Only the mean: the variance is not needed here and costs far more.
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/surface_model.hpp"
#include "touchcloud/types/workspace_parameters.hpp"

namespace touchcloud {

class SurfaceSampler final : public Stage {
  WorkspaceParameters workspace_;
  std::array<int, 2> resolution_{};
  WorkspaceGrid area_;

  void declare_parameters(ParameterSet& p) override {
    workspace_.declare(p, false);
    p.add("resolution", resolution_, std::array<int, 2>{200, 200}).range(2, 4000)
        .doc("lattice points along x and y, edges included");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<SurfaceModelPtr>("surface", "the fitted surface");
    ports.output<CloudConstPtr>("cloud", "surface points (x, y, mean z), base frame, mm");
  }
  void on_check(RunContext&) override { area_ = workspace_.resolve(); }
  void on_configure(RunContext& ctx) override { workspace_.record_used(area_, ctx); }

  void on_process(StageIO& io, RunContext&) override {
    const auto& surface = io.input<SurfaceModelPtr>("surface");
    if (!surface) throw RunError("no surface model");
    // The same model as last time (a touch that added no point): the same
    // points (surface_model.hpp: a model does not change once output).
    if (surface == last_surface_) {
      io.output("cloud", last_cloud_);
      return;
    }
    const int nx = resolution_[0], ny = resolution_[1];
    const Eigen::VectorXd xs = Eigen::VectorXd::LinSpaced(nx, area_.x_mm[0], area_.x_mm[1]);
    const Eigen::VectorXd ys = Eigen::VectorXd::LinSpaced(ny, area_.y_mm[0], area_.y_mm[1]);
    const Eigen::MatrixXd z = surface->mean_on_lattice(xs, ys);
    if (z.rows() != nx || z.cols() != ny) throw RunError("the surface model returned a lattice of the wrong size");
    auto cloud = std::make_shared<PointCloud>();
    cloud->reserve(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!std::isfinite(z(i, j)))
          throw RunError("the surface mean is not finite at (" + std::to_string(xs[i]) + ", " + std::to_string(ys[j]) + ") mm");
        cloud->push_back(pcl::PointXYZ(static_cast<float>(xs[i]), static_cast<float>(ys[j]), static_cast<float>(z(i, j))));
      }
    last_surface_ = surface;
    last_cloud_ = cloud;
    io.output("cloud", last_cloud_);
  }
  SurfaceModelPtr last_surface_;
  CloudConstPtr last_cloud_;
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::SurfaceSampler, "surface_sampler", "Samples a fitted surface's mean on a lattice over the workspace")
