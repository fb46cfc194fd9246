// Adaptive contact saliency (Eq. 4 of the GelStereo Palm 2.0 paper): keep
// marker j when its displacement D[j] exceeds alpha * max(D).
#pragma once

#include <vector>

#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud::saliency {

enum class SalientSelection {
  All,      // every marker above the threshold (the paper's method)
  Deepest,  // only the most displaced marker: one point per touch (baseline SP)
};

// Indices of the salient markers, in cloud order. Empty when nothing moved
// (max displacement 0): there is no contact to extract.
std::vector<std::size_t> salient_markers(const std::vector<double>& displacement_mm, double alpha,
                                         SalientSelection selection);

// The salient markers' current positions, in the sensor frame or mapped into
// the base frame with the cloud's pose.
CloudPtr salient_cloud(const TactileCloud& tactile, const std::vector<std::size_t>& indices, Frame frame);

}  // namespace touchcloud::saliency
