// Convergence of a score over touches (the paper's "convergence steps"): the
// touch count after which the score stays within a tolerance of its final
// value.
#pragma once

#include <vector>

namespace touchcloud::chamfer {

// 1-based count of touches after which every later score is within
// `tolerance` (relative) of the last one; scores.size() when only the last is.
// 0 for no scores.
int convergence_touches(const std::vector<double>& scores, double tolerance = 0.05);

}  // namespace touchcloud::chamfer
