// stable_contact: decides when a touch has settled (Eq. 2-3 of the GelStereo
// Palm 2.0 paper). With T0 the no-contact marker cloud and Ti the cloud at
// frame i, D_i[j] = |Ti[j] - T0[j]| and d_i = max_j D_i[j]. A counter n_i
// grows by one per frame while d_i > l and returns to 0 otherwise; the
// contact is stable when n_i > s. Paper: l = 2 mm, s = 10 frames.
#include <algorithm>
#include <cmath>

#include "touchcloud/plugin.hpp"
#include "touchcloud/types/contact_state.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud {

class StableContact final : public Stage {
  double threshold_mm_ = 2.0;
  int frames_ = 10;
  int counter_ = 0;
  bool was_stable_ = false;
  long frames_since_stable_ = 0;  // frames since the last stable one (or the start)

  void declare_parameters(ParameterSet& p) override {
    p.add("threshold_mm", threshold_mm_, 2.0).unit("mm").above(0.0)
        .doc("l: a frame is in contact when its largest marker displacement exceeds this");
    p.add("frames", frames_, 10).unit("frames").at_least(0)
        .doc("s: the contact is stable once more than this many frames in a row were in contact");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<TactileCloudPtr>("tactile", "marker cloud with its no-contact reference");
    ports.output<ContactState>("state", "max displacement, consecutive-contact counter, stable flag");
  }

  static double max_displacement_mm(const TactileCloud& t) {
    if (!t.points || !t.reference) throw RunError("the tactile cloud lacks its points or its reference cloud");
    if (t.points->size() != t.reference->size())
      throw RunError("the tactile cloud has " + std::to_string(t.points->size()) + " points but its reference has " +
                     std::to_string(t.reference->size()) + "; Eq. 2 pairs them marker by marker");
    if (t.points->empty()) throw RunError("the tactile cloud is empty");
    double d = 0;
    for (std::size_t j = 0; j < t.points->size(); ++j) {
      const auto& p = (*t.points)[j];
      const auto& q = (*t.reference)[j];
      const double dj = std::sqrt(double(p.x - q.x) * double(p.x - q.x) + double(p.y - q.y) * double(p.y - q.y) +
                                  double(p.z - q.z) * double(p.z - q.z));
      if (!std::isfinite(dj)) throw RunError("marker " + std::to_string(j) + " of the tactile cloud is not finite");
      d = std::max(d, dj);
    }
    return d;
  }

  void on_configure(RunContext&) override {
    counter_ = 0;
    was_stable_ = false;
    frames_since_stable_ = 0;
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& tactile = io.input<TactileCloudPtr>("tactile");
    if (!tactile) throw RunError("no tactile cloud");
    ContactState state;
    state.max_displacement_mm = max_displacement_mm(*tactile);
    counter_ = state.max_displacement_mm > threshold_mm_ ? counter_ + 1 : 0;
    state.consecutive_frames = counter_;
    state.stable = counter_ > frames_;
    ++frames_since_stable_;
    // Once per settling: the frames it took since the previous stable frame.
    if (state.stable && !was_stable_) ctx.metric("frames_to_stable", static_cast<double>(frames_since_stable_), "frames");
    if (state.stable) frames_since_stable_ = 0;
    was_stable_ = state.stable;
    io.output("state", state);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::StableContact, "stable_contact", geometry,
                  "Stable contact from marker displacements (GelStereo Palm 2.0, Eq. 2-3)")
