#include "touchcloud/markers/stereo_tracker.hpp"

#include <algorithm>

#include "touchcloud/error.hpp"
#include "touchcloud/number_text.hpp"

namespace touchcloud::markers {

StereoMarkerTracker::StereoMarkerTracker(RestingGelMatcher matcher, TrackerGates gates)
    : matcher_(std::move(matcher)), gates_(gates) {}

MarkerSet StereoMarkerTracker::process(const MarkerSet& frame) {
  return have_reference_ ? track(frame) : start_reference(frame);
}

MarkerSet StereoMarkerTracker::start_reference(const MarkerSet& in) {
  if (in.left.empty() || in.right.empty())
    throw InputError(std::string("input 'markers': the reference (first, no-contact) frame has no markers in the ") +
                     (in.left.empty() ? "left" : "right") + " view; the ids of every later frame come from it");
  MarkerSet out = in;
  for (auto& m : out.left) m.id = -1;  // ids are the tracker's to give
  for (auto& m : out.right) m.id = -1;
  out.matches = matcher_.match(in.left, in.right, gates_.match_gate_px);
  // With the right sensor model nearly every marker seen twice pairs up; a
  // wrong one pairs only the few that land near some marker by chance.
  const std::size_t fewer = std::min(in.left.size(), in.right.size());
  if (2 * out.matches.size() < fewer)
    throw InputError("input 'markers': only " + std::to_string(out.matches.size()) + " of the reference frame's " +
                     std::to_string(in.left.size()) + " left and " + std::to_string(in.right.size()) +
                     " right markers pair up within " + number_text(gates_.match_gate_px) +
                     " px of where the sensor model puts them; check the 'sensor' file (calibration) and "
                     "match_gate_px");
  std::vector<Eigen::Vector2d> left_px, right_px;
  for (std::size_t id = 0; id < out.matches.size(); ++id) {
    MarkerMatch& m = out.matches[id];
    m.id = static_cast<int>(id);
    out.left[m.left].id = out.right[m.right].id = m.id;
    left_px.push_back(in.left[m.left].centre_px);
    right_px.push_back(in.right[m.right].centre_px);
  }
  left_.start(std::move(left_px));
  right_.start(std::move(right_px));
  reference_pairs_ = out.matches.size();
  joined_ = 0;
  have_reference_ = true;
  return out;
}

void StereoMarkerTracker::join_new_pairs(const MarkerSet& in, std::vector<int>& left_ids, std::vector<int>& right_ids) {
  std::vector<Marker> free_left, free_right;
  std::vector<std::size_t> left_at, right_at;
  for (std::size_t i = 0; i < left_ids.size(); ++i)
    if (left_ids[i] < 0) free_left.push_back(in.left[i]), left_at.push_back(i);
  for (std::size_t i = 0; i < right_ids.size(); ++i)
    if (right_ids[i] < 0) free_right.push_back(in.right[i]), right_at.push_back(i);
  if (free_left.empty() || free_right.empty()) return;
  for (const MarkerMatch& m : matcher_.match(free_left, free_right, gates_.join_gate_px)) {
    const int id = left_.add(free_left[m.left].centre_px);
    right_.add(free_right[m.right].centre_px);
    left_ids[left_at[m.left]] = right_ids[right_at[m.right]] = id;
    ++joined_;
  }
}

MarkerSet StereoMarkerTracker::track(const MarkerSet& in) {
  MarkerSet out = in;
  out.matches.clear();
  std::vector<int> left_ids = left_.update(in.left, gates_.rest_gate_px, gates_.track_gate_px);
  std::vector<int> right_ids = right_.update(in.right, gates_.rest_gate_px, gates_.track_gate_px);
  if (gates_.join_gate_px > 0) join_new_pairs(in, left_ids, right_ids);
  std::vector<int> right_of(left_.ids(), -1);
  for (std::size_t r = 0; r < right_ids.size(); ++r) {
    out.right[r].id = right_ids[r];
    if (right_ids[r] >= 0) right_of[right_ids[r]] = static_cast<int>(r);
  }
  for (std::size_t l = 0; l < left_ids.size(); ++l) {
    const int id = left_ids[l];
    out.left[l].id = id;
    if (id >= 0 && right_of[id] >= 0) out.matches.push_back({static_cast<int>(l), right_of[id], id});
  }
  std::sort(out.matches.begin(), out.matches.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

}  // namespace touchcloud::markers
