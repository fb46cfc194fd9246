// marker_matching: stereo correspondences and ids for detected markers; the
// first frame is the no-contact reference (see stereo_tracker.hpp).
#include <algorithm>
#include <limits>

#include "touchcloud/markers/stereo_tracker.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/plugin_kit/sensor_parameters.hpp"

namespace touchcloud {

class MarkerMatching final : public Stage {
  sensor::SensorParameters sensor_;
  markers::TrackerGates gates_;
  sensor::GelStereoSensor sensor_read_;  // read at check

  std::unique_ptr<markers::StereoMarkerTracker> tracker_;
  std::size_t frames_ = 0;
  std::size_t fewest_matched_ = std::numeric_limits<std::size_t>::max();
  double matched_sum_ = 0, left_only_sum_ = 0, right_only_sum_ = 0;

  void declare_parameters(ParameterSet& p) override {
    sensor_.declare(p, "sensor description: a scene or sensor file with a 'sensor:' section (cameras, plate, gel)");
    p.add("match_gate_px", gates_.match_gate_px, 4.0).unit("px").above(0.0)
        .doc("reference frame: a right marker pairs with a left one within this distance of its predicted pixel");
    p.add("track_gate_px", gates_.track_gate_px, 6.0).unit("px").above(0.0)
        .doc("later frames: a marker is looked for within this distance of where it was last seen");
    p.add("rest_gate_px", gates_.rest_gate_px, 1.0).unit("px").above(0.0)
        .doc("later frames: a marker within this distance of its no-contact pixel is taken as back at rest");
    p.add("join_gate_px", gates_.join_gate_px, 1.0).unit("px").at_least(0.0)
        .doc("later frames: an unpaired marker gets an id when both views see it this close to where the resting "
             "gel puts it (0: only the reference frame's markers get ids)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<MarkerSetPtr>("markers", "detected markers of both views (the first frame: no contact)");
    ports.output<MarkerSetPtr>("markers", "the same markers with ids, and the left/right pairs");
    ports.metric("reference_pairs", "markers", "left/right pairs in the reference frame").final();
    ports.metric("joined_later", "markers", "markers tracked from a later frame than the reference").final();
    ports.metric("matched_mean", "markers", "matched pairs per frame, on average").final().higher_is_better();
    ports.metric("matched_fewest", "markers", "matched pairs in the frame with the fewest").final().higher_is_better();
    ports.metric("left_only_mean", "markers", "markers seen only in the left view per frame, on average").final();
    ports.metric("right_only_mean", "markers", "markers seen only in the right view per frame, on average").final();
  }

  void on_check(RunContext&) override { sensor_read_ = sensor_.load(true); }

  void on_configure(RunContext&) override {
    const auto& sensor = sensor_read_;
    tracker_ = std::make_unique<markers::StereoMarkerTracker>(
        markers::RestingGelMatcher(sensor_.rig(sensor, true),
                                    sensor.sensor_from_left_camera().inverse(), sensor.gel.radius_mm()),
        gates_);
  }

  void on_process(StageIO& io, RunContext&) override {
    const auto& in = io.input<MarkerSetPtr>("markers");
    if (!in) throw InputError("input 'markers' is empty");
    if (!in->stereo())
      throw InputError(std::string("input 'markers' holds one camera's markers (view ") +
                       camera_view_name(in->views.at(0)) +
                       "); marker_matching pairs the left and right views of a stereo frame");
    auto out = std::make_shared<MarkerSet>(tracker_->process(*in));
    const std::size_t matched = out->matches.size();
    fewest_matched_ = std::min(fewest_matched_, matched);
    matched_sum_ += static_cast<double>(matched);
    left_only_sum_ += static_cast<double>(in->left.size() - matched);
    right_only_sum_ += static_cast<double>(in->right.size() - matched);
    ++frames_;
    io.output("markers", MarkerSetPtr(out));
  }

  void on_finish(RunContext& ctx) override {
    if (frames_ == 0) return;
    const double n = static_cast<double>(frames_);
    ctx.metric("reference_pairs", static_cast<double>(tracker_->reference_pairs()), "markers");
    ctx.metric("joined_later", static_cast<double>(tracker_->joined_later()), "markers");
    ctx.metric("matched_mean", matched_sum_ / n, "markers");
    ctx.metric("matched_fewest", static_cast<double>(fewest_matched_), "markers");
    ctx.metric("left_only_mean", left_only_sum_ / n, "markers");
    ctx.metric("right_only_mean", right_only_sum_ / n, "markers");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MarkerMatching, "marker_matching", image_to_markers,
                  "Pairs left/right markers through the sensor model and tracks their ids from the reference frame")
