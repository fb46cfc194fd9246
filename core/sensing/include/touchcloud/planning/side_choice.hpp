// Touches from any side on an implicit surface (side_touch): candidate
// contacts on the predicted surface (points sampled on its zero level set),
// each with the model's outward normal (the signed distance's gradient) and
// variance, scored by the variance a press there would take: the summed
// variance of the candidates inside the gel's likely contact patch (within
// footprint_radius_mm of the candidate across its normal, within depth_mm of
// its tangent plane). Candidates sampled uniformly by area stand for equal
// areas, so the sum is the patch's variance integrated over its area, up to a
// constant. The palm then presses against the normal.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/types/implicit_model.hpp"

namespace touchcloud::planning {

struct SideCandidate {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d outward = Eigen::Vector3d::UnitZ();  // unit
  double variance_mm2 = 0;
  double footprint_variance_mm2 = 0;  // the score
};

struct SideChoiceOptions {
  int candidates = 150;
  double footprint_radius_mm = 12.0;
  double depth_mm = 5.5;
  double gradient_step_mm = 0.5;  // central differences of the mean
};

// Candidates drawn (seeded) from `surface_mm`, best first. A candidate where
// the mean's gradient vanishes is left out. InputError when `surface_mm` is empty.
std::vector<SideCandidate> side_candidates(const ImplicitModel& model, const std::vector<Eigen::Vector3d>& surface_mm,
                                           const SideChoiceOptions& options, std::uint64_t seed);

// The press directions to try at a candidate, in turn: against its normal
// (-outward), then turned from that towards straight down by each of
// `oblique_deg` (a dome can press a surface obliquely: a cup's inner wall,
// hidden along its normal behind the far wall, is reached through the
// opening). A tilt past straight down stops there; a press already straight
// down, or straight up, has no oblique ones. The first is -outward as given,
// the others unit vectors.
std::vector<Eigen::Vector3d> press_directions(const Eigen::Vector3d& outward, const std::vector<double>& oblique_deg);

// A start before any model: straight down first, then `count` - 1 directions
// `tilt_deg` from it, evenly round the vertical (unit approach directions).
std::vector<Eigen::Vector3d> start_directions(int count, double tilt_deg);

}  // namespace touchcloud::planning
