// dedup: accumulates the salient clouds of successive touches without
// duplicating overlapping contact areas (Eq. 7).
#include "overlap_filter.hpp"
#include "touchcloud/plugin.hpp"

namespace touchcloud {

class Dedup final : public Stage {
  double threshold_mm_ = 1.8;
  bool enabled_ = true;
  dedup::OverlapTest overlap_ = dedup::OverlapTest::distance;
  std::unique_ptr<dedup::OverlapFilter> filter_;

  void declare_parameters(ParameterSet& p) override {
    p.add("threshold_mm", threshold_mm_, 1.8).unit("mm").above(0.0)
        .doc("a new point closer than this to a kept point is a duplicate (mean marker spacing)");
    p.add("enabled", enabled_, true).doc("false keeps every point (the w/o PCP baseline)");
    p.add("overlap", overlap_, dedup::OverlapTest::distance,
          {{"distance", dedup::OverlapTest::distance}, {"height", dedup::OverlapTest::height}})
        .doc("distance: within threshold_mm in 3D (Eq. 7); height: a kept point within threshold_mm in (x, y) "
             "covers a new one unless the new one lies more than threshold_mm below it (a sensor whose errors "
             "lie above the surface)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<CloudConstPtr>("cloud", "points of the latest touch, base frame");
    ports.output<CloudConstPtr>("accumulated", "every point kept so far");
    ports.output<CloudConstPtr>("added", "the points this touch added");
  }
  void on_configure(RunContext&) override { filter_ = std::make_unique<dedup::OverlapFilter>(threshold_mm_, overlap_); }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& cloud = io.input<CloudConstPtr>("cloud");
    if (!cloud) throw RunError("no cloud to add");
    const CloudPtr added = enabled_ ? filter_->add(*cloud) : filter_->add_all(*cloud);
    ctx.metric("added_points", static_cast<double>(added->size()), "points");
    ctx.metric("total_points", static_cast<double>(filter_->kept().size()), "points");
    io.output("added", CloudConstPtr(added));
    if (io.wants("accumulated")) io.output("accumulated", CloudConstPtr(std::make_shared<PointCloud>(filter_->kept())));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::Dedup, "dedup", geometry, "Accumulates touches, dropping points that overlap earlier ones (Eq. 7)")
