// saliency: the contact patch of a tactile cloud (Eq. 4), in the base frame.
#include <cmath>

#include "salient_points.hpp"
#include "touchcloud/plugin.hpp"

namespace touchcloud {

class Saliency final : public Stage {
  double alpha_ = 0.2;
  saliency::SalientSelection keep_ = saliency::SalientSelection::All;
  Frame frame_ = Frame::Base;
  std::size_t last_count_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("alpha", alpha_, 0.2).at_least(0.0).below(1.0)  // at 1 nothing is above alpha * max
        .doc("keep markers displaced more than alpha * max displacement");
    p.add("keep", keep_, saliency::SalientSelection::All, {{"all", saliency::SalientSelection::All}, {"deepest", saliency::SalientSelection::Deepest}})
        .doc("all salient markers, or only the most displaced one (the single-point baseline SP)");
    p.add("frame", frame_, Frame::Base, {{"base", Frame::Base}, {"sensor", Frame::Sensor}}).doc("frame of the output cloud");
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
    const auto indices = saliency::salient_markers(tactile->displacement_mm, alpha_,
                                         keep_);
    if (indices.empty()) throw RunError("no marker moved: the recorded frame shows no contact");
    last_count_ = indices.size();
    ctx.metric("salient_points", static_cast<double>(last_count_), "points");
    io.output("cloud", CloudConstPtr(saliency::salient_cloud(*tactile, indices, frame_)));
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::Saliency, "saliency", geometry, "Keeps the markers of the contact patch (adaptive threshold, Eq. 4)")
