// saliency: the contact patch of a tactile cloud (Eq. 4), in the base frame.
#include <cmath>

#include "salient_points.hpp"
#include "touchcloud/plugin.hpp"

namespace touchcloud {

class Saliency final : public Stage {
  double alpha_ = 0.2;
  std::string keep_, frame_;
  std::size_t last_count_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("alpha", alpha_, 0.2).at_least(0.0).below(1.0)  // at 1 nothing is above alpha * max
        .doc("keep markers displaced more than alpha * max displacement");
    p.add("keep", keep_, std::string("all"))
        .choices({"all", "deepest"})
        .doc("all salient markers, or only the most displaced one (the single-point baseline SP)");
    p.add("frame", frame_, std::string("base")).choices({"base", "sensor"}).doc("frame of the output cloud");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<TactileCloudPtr>("tactile", "the recorded tactile cloud with displacements");
    ports.output<CloudConstPtr>("cloud", "salient marker positions, mm");
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& tactile = io.input<TactileCloudPtr>("tactile");
    if (!tactile || !tactile->points) throw RunError("the tactile cloud is empty");
    if (tactile->displacement_mm.size() != tactile->points->size())
      throw RunError("the tactile cloud has " + std::to_string(tactile->points->size()) + " points but " +
                     std::to_string(tactile->displacement_mm.size()) + " displacements");
    for (double d : tactile->displacement_mm)
      if (!std::isfinite(d)) throw RunError("the tactile cloud has a non-finite displacement");
    const auto indices = salient_markers(tactile->displacement_mm, alpha_,
                                         keep_ == "deepest" ? SalientSelection::Deepest : SalientSelection::All);
    if (indices.empty()) throw RunError("no marker moved: the recorded frame shows no contact");
    last_count_ = indices.size();
    ctx.metric("salient_points", static_cast<double>(last_count_), "points");
    io.output("cloud", CloudConstPtr(salient_cloud(*tactile, indices, frame_ == "base" ? Frame::Base : Frame::Sensor)));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::Saliency, "saliency", "Keeps the markers of the contact patch (adaptive threshold, Eq. 4)")
