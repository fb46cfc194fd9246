// pose_noise: the pose the robot reports for a frame, the truth perturbed by
// seeded Gaussian noise (translation sigma_mm per axis, rotation sigma_deg
// per axis), keyed by the frame number alone.
#pragma once

#include <cstdint>

#include <Eigen/Geometry>

#include "touchcloud/simulation/scene/effects.hpp"

namespace touchcloud::simulation {

Eigen::Isometry3d noisy_pose(const Eigen::Isometry3d& truth, const EffectParameters& p, std::uint64_t noise_seed,
                             std::uint64_t stream, std::uint64_t frame);

}  // namespace touchcloud::simulation
