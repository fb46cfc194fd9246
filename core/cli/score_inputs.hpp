// What `touchcloud score` scores: the EST arguments expanded into pairs of
// estimate and ground truth. An argument may be a cloud file, a folder (every
// .pcd and .ply under it, as `touchcloud run` writes them), a glob, or a CSV
// manifest of "estimate, ground truth" rows.
#pragma once

#include <string>
#include <vector>

namespace touchcloud::cli {

struct ScorePair {
  std::string estimate;      // as it will be opened
  std::string ground_truth;  // empty: none given (an error for this pair)
  std::string error;         // set when the argument itself could not be expanded
};

// Pairs in argument order; `default_gt` (from --gt) serves every pair that
// names none. A malformed manifest is bad input (InputError with FILE:LINE).
std::vector<ScorePair> expand_score_arguments(const std::vector<std::string>& arguments,
                                              const std::string& default_gt);

}  // namespace touchcloud::cli
