// One camera's markers matched to those of the no-contact frame: a marker of
// the reference and one of the frame are the same dot when each is the
// other's nearest and they are at most `max_distance_px` apart. Nearest
// neighbours rather than optical flow: a pressed dot moves a few pixels, well
// under half the distance between dots, so the nearest dot is the same dot;
// the centres alone suffice (no image windows, no pyramid), and a dot that
// moved past the limit, or vanished, is left unmatched instead of being
// followed by guess. Brute force: a gel carries a few hundred dots.
#pragma once

#include <vector>

#include "touchcloud/types/displacement_field.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::imaging {

// The field's markers (rest, displacement) and counts; mm_per_px and the
// timestamp are left for the caller.
DisplacementField match_to_reference(const std::vector<Marker>& reference, const std::vector<Marker>& frame,
                                     double max_distance_px);

}  // namespace touchcloud::imaging
