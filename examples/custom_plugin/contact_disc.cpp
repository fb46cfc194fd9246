// contact_disc: keeps the points of a cloud within a radius of the gel's
// axis, the disc where a palm sensor's contact is most reliable. A complete
// plugin in one file: parameters, ports, a process hook and a metric.
#include <touchcloud/plugin.hpp>
#include <touchcloud/types/point_cloud.hpp>

namespace {

class ContactDisc final : public touchcloud::Stage {
  double radius_mm_ = 20.0;
  std::vector<double> centre_mm_;
  std::size_t kept_ = 0;

  void declare_parameters(touchcloud::ParameterSet& p) override {
    p.add("radius_mm", radius_mm_, 20.0).unit("mm").above(0.0).doc("radius of the disc kept, around the centre");
    p.add("centre_mm", centre_mm_, std::vector<double>{0.0, 0.0}).unit("mm").size(2).doc("disc centre (x, y)");
  }
  void declare_ports(touchcloud::PortSet& ports) override {
    ports.input<touchcloud::CloudConstPtr>("cloud", "points, mm");
    ports.output<touchcloud::CloudConstPtr>("cloud", "points within the disc");
  }
  void on_process(touchcloud::StageIO& io, touchcloud::RunContext&) override {
    const auto& in = io.input<touchcloud::CloudConstPtr>("cloud");
    auto out = std::make_shared<touchcloud::PointCloud>();
    for (const auto& q : in->points) {
      const double dx = q.x - centre_mm_[0], dy = q.y - centre_mm_[1];
      if (dx * dx + dy * dy <= radius_mm_ * radius_mm_) out->push_back(q);
    }
    kept_ = out->size();
    io.output("cloud", touchcloud::CloudConstPtr(out));
  }
  void on_finish(touchcloud::RunContext& ctx) override { ctx.metric("points_kept", static_cast<double>(kept_), "points"); }
};

}  // namespace

TOUCHCLOUD_PLUGIN(ContactDisc, "contact_disc", geometry, "Keeps the points within a disc around the gel axis")
