// Test plugin: an analytic surface model, z = slope_x x + slope_y y + offset,
// whose variance is the squared distance to `peak` (so its argmax is known);
// with `correlation_mm` set, also a covariance: sqrt(v_i v_j) times a
// Gaussian of the distance.
#include <cmath>
#include <optional>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/surface_model.hpp"

namespace {

class PlaneSurface final : public touchcloud::SurfaceModel {
 public:
  PlaneSurface(std::vector<double> slope, double offset, std::vector<double> peak, std::optional<double> correlation_mm)
      : slope_(std::move(slope)), offset_(offset), peak_(std::move(peak)), correlation_mm_(correlation_mm) {}
  std::size_t training_size() const override { return 0; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override {
    return (xy.col(0) * slope_[0] + xy.col(1) * slope_[1]).array() + offset_;
  }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override {
    return (xy.col(0).array() - peak_[0]).square() + (xy.col(1).array() - peak_[1]).square();
  }
  std::optional<Eigen::MatrixXd> covariance(const Eigen::MatrixX2d& xy) const override {
    if (!correlation_mm_) return std::nullopt;
    const Eigen::VectorXd sd = variance(xy).cwiseSqrt();
    Eigen::MatrixXd s(xy.rows(), xy.rows());
    for (Eigen::Index i = 0; i < xy.rows(); ++i)
      for (Eigen::Index j = 0; j < xy.rows(); ++j)
        s(i, j) = sd[i] * sd[j] *
                  std::exp(-(xy.row(i) - xy.row(j)).squaredNorm() / (2 * *correlation_mm_ * *correlation_mm_));
    return s;
  }
  std::optional<double> noise_variance_mm2() const override { return 0.01; }
  std::map<std::string, double> hyperparameters() const override { return {}; }

 private:
  std::vector<double> slope_;
  double offset_;
  std::vector<double> peak_;
  std::optional<double> correlation_mm_;
};

class PlaneSurfaceStage final : public touchcloud::Stage {
  std::vector<double> slope_, peak_;
  double offset_ = 0;
  std::optional<double> correlation_mm_;
  void declare_parameters(touchcloud::ParameterSet& p) override {
    p.add("slope", slope_, std::vector<double>{0, 0}).size(2).doc("dz/dx, dz/dy");
    p.add("offset_mm", offset_, 0.0).unit("mm").doc("z at the origin");
    p.add("peak_mm", peak_, std::vector<double>{0, 0}).size(2).unit("mm").doc("variance grows with distance from here");
    p.add("correlation_mm", correlation_mm_).unit("mm").doc("not set: no covariance; else its correlation length");
  }
  void declare_ports(touchcloud::PortSet& ports) override {
    ports.output<touchcloud::SurfaceModelPtr>("surface", "the analytic surface");
  }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext&) override {
    io.output("surface", touchcloud::SurfaceModelPtr(std::make_shared<PlaneSurface>(slope_, offset_, peak_, correlation_mm_)));
  }
};

}  // namespace

TOUCHCLOUD_PLUGIN(PlaneSurfaceStage, "test_plane_surface", reconstruction, "Test only: an analytic plane with known variance")
