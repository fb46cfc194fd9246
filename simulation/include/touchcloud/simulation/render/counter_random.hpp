// Counter-based random draws: each value is a pure function of a seed and
// a few counters (frame, view, marker), so an effect's randomness does not
// depend on which other effects run or which outputs are read, and any frame
// can be reproduced on its own.
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>

#include <Eigen/Core>

namespace touchcloud::simulation {

// splitmix64's finaliser: stepping a counter by kGoldenGamma and mixing it is splitmix64.
inline constexpr std::uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;
inline std::uint64_t mix64(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// The streams of draws, one per effect (a key's first counter): one list,
// so that no two effects draw the same numbers.
enum DrawStream : std::uint64_t {
  kPoseNoise = 1, kCentreNoise = 2, kDropout = 3, kImageNoise = 4, kColourNoise = 5,  // GelStereo
  kGelSightPoseNoise = 11, kGelSightImageNoise = 12,
};

// A 64-bit key for (seed, counters...).
inline std::uint64_t draw_key(std::uint64_t seed, std::initializer_list<std::uint64_t> counters) {
  std::uint64_t h = mix64(seed + kGoldenGamma);
  for (std::uint64_t c : counters) h = mix64(h ^ (c + kGoldenGamma));
  return h;
}

// Uniform in (0, 1), never 0 (a log follows).
inline double uniform_from(std::uint64_t key) { return (static_cast<double>(key >> 11) + 0.5) * 0x1.0p-53; }

// Two independent standard normals (Box-Muller).
inline Eigen::Vector2d normal_pair_from(std::uint64_t key) {
  const double r = std::sqrt(-2.0 * std::log(uniform_from(key)));
  const double angle = 2.0 * M_PI * uniform_from(mix64(key ^ kGoldenGamma));
  return {r * std::cos(angle), r * std::sin(angle)};
}

}  // namespace touchcloud::simulation
