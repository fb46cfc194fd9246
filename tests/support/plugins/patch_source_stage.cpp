// Test plugin: each call emits the points of one circular "touch" patch on
// the analytic surface z = 10 + 3 sin(x / 15) cos(y / 20) (mm), at the next
// centre of `centres_mm` (x0, y0, x1, y1, ...), on a square lattice.
#include <cmath>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/point_cloud.hpp"

namespace {

class PatchSource final : public touchcloud::Stage {
  std::vector<double> centres_;
  double radius_mm_ = 8, spacing_mm_ = 1.8;
  std::size_t call_ = 0;
  void declare_parameters(touchcloud::ParameterSet& p) override {
    p.add("centres_mm", centres_, std::vector<double>{0, 0}).unit("mm").doc("patch centres x0, y0, x1, y1, ...");
    p.add("radius_mm", radius_mm_, 8.0).unit("mm").above(0.0).doc("patch radius");
    p.add("spacing_mm", spacing_mm_, 1.8).unit("mm").above(0.0).doc("lattice spacing");
  }
  void declare_ports(touchcloud::PortSet& ports) override {
    ports.output<touchcloud::CloudConstPtr>("cloud", "the patch, mm");
  }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext&) override {
    const std::size_t k = call_++ % (centres_.size() / 2);
    const double cx = centres_[2 * k], cy = centres_[2 * k + 1];
    auto cloud = std::make_shared<touchcloud::PointCloud>();
    const int n = static_cast<int>(radius_mm_ / spacing_mm_);
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) {
        const double x = cx + i * spacing_mm_, y = cy + j * spacing_mm_;
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > radius_mm_ * radius_mm_) continue;
        const double z = 10 + 3 * std::sin(x / 15) * std::cos(y / 20);
        cloud->push_back(pcl::PointXYZ(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
      }
    io.output("cloud", touchcloud::CloudConstPtr(cloud));
  }
};

}  // namespace

TOUCHCLOUD_PLUGIN(PatchSource, "test_patch_source", source, "Test only: touch patches of an analytic surface")
