#include "touchcloud/imaging/marker_displacement.hpp"

#include <limits>

namespace touchcloud::imaging {

namespace {

// Index of the marker of `set` nearest to `p` (-1 for an empty set).
int nearest(const std::vector<Marker>& set, const Eigen::Vector2d& p, double& distance2) {
  int best = -1;
  distance2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < set.size(); ++i) {
    const double d2 = (set[i].centre_px - p).squaredNorm();
    if (d2 < distance2) distance2 = d2, best = static_cast<int>(i);
  }
  return best;
}

}  // namespace

DisplacementField match_to_reference(const std::vector<Marker>& reference, const std::vector<Marker>& frame,
                                     double max_distance_px) {
  DisplacementField field;
  field.reference_markers = reference.size();
  field.frame_markers = frame.size();
  const double limit2 = max_distance_px * max_distance_px;
  for (std::size_t r = 0; r < reference.size(); ++r) {
    double d2 = 0, back2 = 0;
    const int f = nearest(frame, reference[r].centre_px, d2);
    if (f < 0 || d2 > limit2) continue;
    if (nearest(reference, frame[f].centre_px, back2) != static_cast<int>(r)) continue;  // not mutual
    field.markers.push_back({reference[r].centre_px, frame[f].centre_px - reference[r].centre_px});
  }
  return field;
}

}  // namespace touchcloud::imaging
