// surface_sampler: the fitted surface's mean on a regular lattice over the
// workspace (the paper evaluates 200 x 200), as a cloud for scoring and
// writing. Only the mean by default: the variance costs far more, and is
// computed only when `max_sd_mm` asks to mask where the model is unsure.
// Where the mean runs far outside the z range of the data it was fitted to
// (an object the sensor could not reach everywhere), the points are masked
// or the run fails, never passed on silently. Given the fitted points, the
// mean is also held against the points measured beside each lattice point
// (near_data.hpp): a local swing is warned of, or masked, or fails the run.
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "near_data.hpp"

#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/workspace_parameters.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/surface_model.hpp"

namespace touchcloud {

enum class OutsideData { Mask, Error, Keep };
// The names pipelines write, for both checks (outside_data, near_data).
const std::vector<std::pair<std::string, OutsideData>> kOutsideDataChoices = {
    {"mask", OutsideData::Mask}, {"error", OutsideData::Error}, {"keep", OutsideData::Keep}};

class SurfaceSampler final : public Stage {
  WorkspaceParameters workspace_;
  std::array<int, 2> resolution_{};
  WorkspaceGrid area_;
  double outside_margin_mm_ = 20.0;
  OutsideData outside_ = OutsideData::Mask;
  std::optional<double> max_sd_mm_;
  double near_radius_mm_ = 2.0, near_margin_mm_ = 5.0;
  OutsideData near_ = OutsideData::Keep;
  long masked_total_ = 0;
  bool near_warned_ = false;

  void declare_parameters(ParameterSet& p) override {
    workspace_.declare(p, false);
    p.add("resolution", resolution_, std::array<int, 2>{200, 200}).range(2, 4000)
        .doc("lattice points along x and y, edges included");
    p.add("outside_data_margin_mm", outside_margin_mm_, 20.0).unit("mm").above(0)
        .doc("a mean further than this below the lowest or above the highest fitted point is extrapolation");
    p.add("outside_data", outside_, OutsideData::Mask, kOutsideDataChoices)
        .doc("points whose mean is extrapolation: dropped with a warning (mask), fail the run (error), or kept "
             "with a warning (keep)");
    p.add("max_sd_mm", max_sd_mm_).unit("mm").above(0)
        .doc("also drop points whose posterior standard deviation exceeds this (computes the variance on the "
             "lattice, far slower than the mean); not set: no such mask");
    p.add("near_data_radius_mm", near_radius_mm_, 2.0).unit("mm").above(0)
        .doc("with the fitted points wired: the points within this (x, y) distance of a lattice point are its "
             "neighbours (about one marker spacing)");
    p.add("near_data_margin_mm", near_margin_mm_, 5.0).unit("mm").above(0)
        .doc("a mean further than this above or below every neighbouring fitted point swings off its data");
    p.add("near_data", near_, OutsideData::Keep, kOutsideDataChoices)
        .doc("points whose mean swings off the neighbouring data: kept with a warning (keep), dropped with a "
             "warning (mask), or fail the run (error)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<SurfaceModelPtr>("surface", "the fitted surface");
    ports.optional_input<CloudConstPtr>("points", "the points the surface was fitted to, base frame (wire as "
                                        "dedup.accumulated): the mean is checked against those beside it");
    ports.output<CloudConstPtr>("cloud", "surface points (x, y, mean z), base frame, mm");
    ports.metric("extrapolated_points", "points", "lattice points whose mean lies outside the data's z range by more "
                 "than outside_data_margin_mm");
    ports.metric("uncertain_points", "points", "with max_sd_mm: lattice points whose standard deviation exceeds it");
    ports.metric("off_data_points", "points", "with points wired: lattice points whose mean swings off the data beside "
                 "them");
    ports.metric("masked_points", "points", "lattice points dropped by any mask: surface lost, which completeness "
                 "and recall count as missed").role(MetricRole::masked_points);
    ports.metric("lattice_points", "points", "lattice points before any mask").final();
  }
  void on_check(RunContext&) override { area_ = workspace_.resolve(); }
  void on_configure(RunContext& ctx) override { workspace_.record_used(area_, ctx); }

  void on_process(StageIO& io, RunContext& ctx) override {
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
    const Eigen::MatrixXd sd =
        max_sd_mm_ ? Eigen::MatrixXd(surface->variance_on_lattice(xs, ys).cwiseMax(0.0).cwiseSqrt()) : Eigen::MatrixXd();
    const auto range = surface->data_z_range_mm();
    std::optional<surface_sampler::NearDataRange> near;
    if (const auto* points = io.optional_input<CloudConstPtr>("points"); points && *points) {
      try {
        near = surface_sampler::near_data_range(xs, ys, **points, near_radius_mm_);
      } catch (const InputError& e) {
        throw RunError(std::string("the fitted points cannot be checked against: ") + e.what());
      }
    }
    auto cloud = std::make_shared<PointCloud>();
    cloud->reserve(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
    long outside = 0, unsure = 0, off = 0;
    double worst = 0;  // furthest mean outside the data's range, mm
    double worst_off = 0;
    std::array<double, 3> worst_off_at{};
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double zij = z(i, j);
        if (!std::isfinite(zij))
          throw RunError("the surface mean is not finite at (" + std::to_string(xs[i]) + ", " + std::to_string(ys[j]) + ") mm");
        if (range) {
          const double beyond = std::max((*range)[0] - zij, zij - (*range)[1]);
          if (beyond > outside_margin_mm_) {
            ++outside;
            worst = std::max(worst, beyond);
            if (outside_ == OutsideData::Error) throw RunError(outside_message(xs[i], ys[j], zij, *range));
            if (outside_ == OutsideData::Mask) continue;
          }
        }
        if (near) {
          const double beyond = near->beyond(i, j, zij);
          if (beyond > near_margin_mm_) {
            ++off;
            if (beyond > worst_off) {
              worst_off = beyond;
              worst_off_at = {xs[i], ys[j], zij};
            }
            if (near_ == OutsideData::Error) throw RunError(off_data_message(xs[i], ys[j], zij, *near, i, j));
            if (near_ == OutsideData::Mask) continue;
          }
        }
        if (max_sd_mm_ && sd(i, j) > *max_sd_mm_) {
          ++unsure;
          continue;
        }
        cloud->push_back(pcl::PointXYZ(static_cast<float>(xs[i]), static_cast<float>(ys[j]), static_cast<float>(zij)));
      }
    report(outside, unsure, worst, ctx);
    if (near) report_off_data(off, worst_off, worst_off_at, ctx);
    ctx.metric("masked_points", static_cast<double>(static_cast<long>(nx) * ny - static_cast<long>(cloud->size())),
               "points");
    last_counts_ = {outside, off, unsure, static_cast<long>(nx) * ny - static_cast<long>(cloud->size())};
    last_surface_ = surface;
    last_cloud_ = cloud;
    io.output("cloud", last_cloud_);
  }
  std::string outside_message(double x, double y, double z, const std::array<double, 2>& range) const {
    std::ostringstream s;
    s << "the surface mean at (" << x << ", " << y << ") mm is z = " << z << " mm, more than outside_data_margin_mm "
      << outside_margin_mm_ << " outside the fitted points' z range [" << range[0] << ", " << range[1]
      << "] mm: the model extrapolates (an object the sensor could not reach everywhere?)";
    return s.str();
  }

  std::string off_data_message(double x, double y, double z, const surface_sampler::NearDataRange& near, int i,
                               int j) const {
    std::ostringstream s;
    s << "the surface mean at (" << x << ", " << y << ") mm is z = " << z << " mm, more than near_data_margin_mm "
      << near_margin_mm_ << " outside the z range [" << near.lo(i, j) << ", " << near.hi(i, j)
      << "] mm of the fitted points within " << near_radius_mm_ << " mm of it: the surface swings off its data";
    return s.str();
  }

  // Per call: how many points swing off the data beside them, and a warning
  // the first time any do.
  void report_off_data(long off, double worst, const std::array<double, 3>& at, RunContext& ctx) {
    ctx.metric("off_data_points", static_cast<double>(off), "points");
    if (off == 0 || near_warned_) return;
    near_warned_ = true;
    std::ostringstream s;
    s << off << " lattice points lie more than " << near_margin_mm_ << " mm outside the z range of the fitted points "
      << "within " << near_radius_mm_ << " mm of them, up to " << worst << " mm (z = " << at[2] << " mm at ("
      << at[0] << ", " << at[1] << ") mm): " << (near_ == OutsideData::Mask ? "dropped" : "kept")
      << "; the surface swings off its data there";
    ctx.log("warning: " + s.str());
    ctx.note("off_data", s.str());
  }

  // Per call: how many points were masked, and a warning the first time.
  void report(long outside, long unsure, double worst, RunContext& ctx) {
    ctx.metric("extrapolated_points", static_cast<double>(outside), "points");
    if (max_sd_mm_) ctx.metric("uncertain_points", static_cast<double>(unsure), "points");
    if (outside == 0 || masked_total_ > 0) {
      masked_total_ += outside;
      return;
    }
    masked_total_ += outside;
    std::ostringstream s;
    s << outside << " lattice points lie up to " << worst << " mm outside the fitted points' z range (margin "
      << outside_margin_mm_ << " mm): " << (outside_ == OutsideData::Mask ? "dropped" : "kept")
      << "; the surface there is extrapolation, not measurement";
    ctx.log("warning: " + s.str());
    ctx.note("extrapolation", s.str());
  }

  // The warnings' notes hold the last call's counts: a run's summary states
  // what its final surface lost, not what an early touch's did.
  void on_finish(RunContext& ctx) override {
    ctx.metric("lattice_points", static_cast<double>(resolution_[0]) * resolution_[1], "points");
    const auto& [outside, off, unsure, masked] = last_counts_;
    const auto verb = [](OutsideData d) { return d == OutsideData::Mask ? "dropped" : "kept"; };
    if (masked_total_ > 0)
      ctx.note("extrapolation", "at the last call " + std::to_string(outside) + " lattice points lay more than " +
                                    number(outside_margin_mm_) + " mm outside the fitted points' z range (" +
                                    verb(outside_) + "); the surface there is extrapolation, not measurement");
    if (near_warned_)
      ctx.note("off_data", "at the last call " + std::to_string(off) + " lattice points swung more than " +
                               number(near_margin_mm_) + " mm off the fitted points within " +
                               number(near_radius_mm_) + " mm (" + verb(near_) + ")");
    if (masked > 0)
      ctx.note("masked", "at the last call " + std::to_string(masked) + " of " +
                             std::to_string(static_cast<long>(resolution_[0]) * resolution_[1]) +
                             " lattice points were dropped by the masks (outside_data, near_data, max_sd_mm): "
                             "surface lost, counted as missed coverage");
  }
  static std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  std::array<long, 4> last_counts_{};  // extrapolated, off data, uncertain, masked
  SurfaceModelPtr last_surface_;
  CloudConstPtr last_cloud_;
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::SurfaceSampler, "surface_sampler", reconstruction, "Samples a fitted surface's mean on a lattice over the workspace")
