#include "touchcloud/simulation/motion/pose_noise.hpp"

#include <cmath>

#include "touchcloud/simulation/render/counter_random.hpp"

namespace touchcloud::simulation {

Eigen::Isometry3d noisy_pose(const Eigen::Isometry3d& truth, const EffectParameters& p, std::uint64_t noise_seed,
                             std::uint64_t stream, std::uint64_t frame) {
  Eigen::Isometry3d reported = truth;
  const Eigen::Vector2d a = normal_pair_from(draw_key(noise_seed, {stream, frame, 0}));
  const Eigen::Vector2d b = normal_pair_from(draw_key(noise_seed, {stream, frame, 1}));
  const Eigen::Vector2d c = normal_pair_from(draw_key(noise_seed, {stream, frame, 2}));
  const Eigen::Vector3d rotation_rad = Eigen::Vector3d(b.y(), c.x(), c.y()) * (p.pose_sigma_deg * M_PI / 180.0);
  reported.translation() += Eigen::Vector3d(a.x(), a.y(), b.x()) * p.pose_sigma_mm;
  if (rotation_rad.norm() > 0)
    reported.linear() =
        Eigen::AngleAxisd(rotation_rad.norm(), rotation_rad.normalized()).toRotationMatrix() * reported.linear();
  return reported;
}

}  // namespace touchcloud::simulation
