// Test plugin: keeps a growing cloud behind its `cloud` output, as
// gpis_surface keeps its model behind `implicit`, and copies it only when
// something else still holds it then: its `copies` metric counts those calls.
#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace {

class HeldCloud final : public touchcloud::Stage {
  std::shared_ptr<touchcloud::PointCloud> cloud_ = std::make_shared<touchcloud::PointCloud>();
  int calls_ = 0, copies_ = 0;
  void declare_ports(touchcloud::PortSet& ports) override {
    ports.optional_input<touchcloud::CloudConstPtr>("cloud", "read as side_touch reads fit.implicit@previous");
    ports.output<touchcloud::CloudConstPtr>("cloud", "a point more each call");
    ports.metric("points_read", "points", "size of the cloud read");
    ports.metric("copies", "calls", "calls at which another holder forced a copy").final();
  }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext& ctx) override {
    ++calls_;
    if (const auto* in = io.optional_input<touchcloud::CloudConstPtr>("cloud"); in && *in)
      ctx.metric("points_read", static_cast<double>((*in)->size()), "points");
    if (cloud_.use_count() > 1) {
      ++copies_;
      cloud_ = std::make_shared<touchcloud::PointCloud>(*cloud_);
    }
    cloud_->push_back(pcl::PointXYZ(static_cast<float>(calls_), 0.0f, 0.0f));
    if (io.wants("cloud")) io.output<touchcloud::CloudConstPtr>("cloud", cloud_);
  }
  void on_finish(touchcloud::RunContext& ctx) override { ctx.metric("copies", copies_, "calls"); }
};

}  // namespace

TOUCHCLOUD_PLUGIN(HeldCloud, "test_held_cloud", source, "Test only: a cloud kept behind an output, copied when shared")
