// marker_matching: stereo correspondences and ids for detected markers. The
// first frame is the no-contact reference: its left and right markers are
// paired through the sensor model (RestingGelMatcher) and each pair gets a
// marker id. Every later frame follows those ids in each view
// (ViewTracker: a marker is first looked for at its no-contact pixel, then
// near where it was last seen); it is matched in a frame when both views
// found it.
// A marker missing from the reference (dropped out, occluded) joins later
// when both views see it where the resting gel puts it (within
// join_gate_px), so its first position is still a no-contact one. Markers
// seen in one view only are reported, never paired by guess.
#include <algorithm>
#include <limits>

#include "stereo_matcher.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "view_tracker.hpp"

namespace touchcloud {

class MarkerMatching final : public Stage {
  std::string sensor_file_;
  bool lens_distortion_ = false;
  double match_gate_px_ = 4.0, track_gate_px_ = 6.0, rest_gate_px_ = 1.0, join_gate_px_ = 1.0;

  std::unique_ptr<matching::RestingGelMatcher> matcher_;
  matching::ViewTracker left_, right_;
  bool have_reference_ = false;
  std::size_t reference_pairs_ = 0, joined_ = 0, frames_ = 0;
  std::size_t fewest_matched_ = std::numeric_limits<std::size_t>::max();
  double matched_sum_ = 0, left_only_sum_ = 0, right_only_sum_ = 0;

  void declare_parameters(ParameterSet& p) override {
    p.add("sensor", sensor_file_, std::string()).input_file()
        .doc("sensor description: a scene or sensor file with a 'sensor:' section (cameras, plate, gel)");
    p.add("lens_distortion", lens_distortion_, false).doc("apply the sensor file's lens distortion coefficients");
    p.add("match_gate_px", match_gate_px_, 4.0).unit("px").above(0.0)
        .doc("reference frame: a right marker pairs with a left one within this distance of its predicted pixel");
    p.add("track_gate_px", track_gate_px_, 6.0).unit("px").above(0.0)
        .doc("later frames: a marker is looked for within this distance of where it was last seen");
    p.add("rest_gate_px", rest_gate_px_, 1.0).unit("px").above(0.0)
        .doc("later frames: a marker within this distance of its no-contact pixel is taken as back at rest");
    p.add("join_gate_px", join_gate_px_, 1.0).unit("px").at_least(0.0)
        .doc("later frames: an unpaired marker gets an id when both views see it this close to where the resting "
             "gel puts it (0: only the reference frame's markers get ids)");
  }
  void declare_ports(PortSet& ports) override {
    ports.input<MarkerSetPtr>("markers", "detected markers of both views (the first frame: no contact)");
    ports.output<MarkerSetPtr>("markers", "the same markers with ids, and the left/right pairs");
  }

  void on_check(RunContext&) override {
    try {
      sensor::make_stereo_rig(sensor::load_gelstereo_sensor(sensor_file_), true, lens_distortion_);
    } catch (const InputError& e) {
      throw ParameterError("sensor", e.what());
    }
  }

  void on_configure(RunContext&) override {
    const auto sensor = sensor::load_gelstereo_sensor(sensor_file_);
    matcher_ = std::make_unique<matching::RestingGelMatcher>(
        sensor::make_stereo_rig(sensor, true, lens_distortion_), sensor.sensor_from_left_camera().inverse(),
        sensor.gel.radius_mm());
    have_reference_ = false;
  }

  std::shared_ptr<MarkerSet> start_reference(const MarkerSet& in) {
    if (in.left.empty() || in.right.empty())
      throw InputError(std::string("input 'markers': the reference (first, no-contact) frame has no markers in the ") +
                       (in.left.empty() ? "left" : "right") + " view; the ids of every later frame come from it");
    auto out = std::make_shared<MarkerSet>(in);
    for (auto& m : out->left) m.id = -1;  // ids are this stage's to give
    for (auto& m : out->right) m.id = -1;
    out->matches = matcher_->match(in.left, in.right, match_gate_px_);
    // With the right sensor model nearly every marker seen twice pairs up; a
    // wrong one pairs only the few that land near some marker by chance.
    const std::size_t fewer = std::min(in.left.size(), in.right.size());
    if (2 * out->matches.size() < fewer)
      throw InputError("input 'markers': only " + std::to_string(out->matches.size()) + " of the reference frame's " +
                       std::to_string(in.left.size()) + " left and " + std::to_string(in.right.size()) +
                       " right markers pair up within " + format_value(ParamValue(match_gate_px_)) +
                       " px of where the sensor model puts them; check the 'sensor' file (calibration) and "
                       "match_gate_px");
    std::vector<Eigen::Vector2d> left_px, right_px;
    for (std::size_t id = 0; id < out->matches.size(); ++id) {
      MarkerMatch& m = out->matches[id];
      m.id = static_cast<int>(id);
      out->left[m.left].id = out->right[m.right].id = m.id;
      left_px.push_back(in.left[m.left].centre_px);
      right_px.push_back(in.right[m.right].centre_px);
    }
    left_.start(std::move(left_px));
    right_.start(std::move(right_px));
    reference_pairs_ = out->matches.size();
    joined_ = 0;
    have_reference_ = true;
    return out;
  }

  // Markers without an id in both views that sit where the resting gel puts
  // them become new pairs.
  void join_new_pairs(const MarkerSet& in, std::vector<int>& left_ids, std::vector<int>& right_ids) {
    std::vector<Marker> free_left, free_right;
    std::vector<std::size_t> left_at, right_at;
    for (std::size_t i = 0; i < left_ids.size(); ++i)
      if (left_ids[i] < 0) free_left.push_back(in.left[i]), left_at.push_back(i);
    for (std::size_t i = 0; i < right_ids.size(); ++i)
      if (right_ids[i] < 0) free_right.push_back(in.right[i]), right_at.push_back(i);
    if (free_left.empty() || free_right.empty()) return;
    for (const MarkerMatch& m : matcher_->match(free_left, free_right, join_gate_px_)) {
      const int id = left_.add(free_left[m.left].centre_px);
      right_.add(free_right[m.right].centre_px);
      left_ids[left_at[m.left]] = right_ids[right_at[m.right]] = id;
      ++joined_;
    }
  }

  std::shared_ptr<MarkerSet> track(const MarkerSet& in) {
    auto out = std::make_shared<MarkerSet>(in);
    out->matches.clear();
    std::vector<int> left_ids = left_.update(in.left, rest_gate_px_, track_gate_px_);
    std::vector<int> right_ids = right_.update(in.right, rest_gate_px_, track_gate_px_);
    if (join_gate_px_ > 0) join_new_pairs(in, left_ids, right_ids);
    std::vector<int> right_of(left_.ids(), -1);
    for (std::size_t r = 0; r < right_ids.size(); ++r) {
      out->right[r].id = right_ids[r];
      if (right_ids[r] >= 0) right_of[right_ids[r]] = static_cast<int>(r);
    }
    for (std::size_t l = 0; l < left_ids.size(); ++l) {
      const int id = left_ids[l];
      out->left[l].id = id;
      if (id >= 0 && right_of[id] >= 0) out->matches.push_back({static_cast<int>(l), right_of[id], id});
    }
    std::sort(out->matches.begin(), out->matches.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    return out;
  }

  void on_process(StageIO& io, RunContext&) override {
    const auto& in = io.input<MarkerSetPtr>("markers");
    if (!in) throw InputError("input 'markers' is empty");
    auto out = have_reference_ ? track(*in) : start_reference(*in);
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
    ctx.metric("reference_pairs", static_cast<double>(reference_pairs_), "markers");
    ctx.metric("joined_later", static_cast<double>(joined_), "markers");
    ctx.metric("matched_mean", matched_sum_ / n, "markers");
    ctx.metric("matched_fewest", static_cast<double>(fewest_matched_), "markers");
    ctx.metric("left_only_mean", left_only_sum_ / n, "markers");
    ctx.metric("right_only_mean", right_only_sum_ / n, "markers");
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::MarkerMatching, "marker_matching",
                  "Pairs left/right markers through the sensor model and tracks their ids from the reference frame")
