// Uniform sampling of a triangle mesh's surface by area.
#include <algorithm>
#include <cmath>
#include <random>

#include "area_lookup.hpp"
#include "touchcloud/parallel_ranges.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

namespace touchcloud::scoring {

namespace {

// Each block of samples draws from its own generator, seeded from the seed
// and the block number, so the points do not depend on the thread count.
constexpr std::size_t kSamplesPerBlock = 1 << 16;

double triangle_area(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const Eigen::Vector3d& a = mesh.vertices[t[0]];
  return 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
}

// A double in [0, 1) from the top 53 bits: unlike
// std::uniform_real_distribution, the same on every standard library.
double unit_draw(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

double surface_area_mm2(const TriangleMesh& mesh) {
  double area = 0;
  for (const auto& t : mesh.triangles) area += triangle_area(mesh, t);
  return area;
}

Points sample_surface(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed, int threads) {
  for (const auto& t : mesh.triangles)
    for (std::uint32_t v : t)
      if (v >= mesh.vertices.size())
        throw InputError("triangle vertex index " + std::to_string(v) + " is past the " +
                         std::to_string(mesh.vertices.size()) + " vertices");
  // Cumulative areas: a draw r in [0, total) lands in the first triangle whose
  // running total exceeds r, so a triangle is hit in proportion to its area and
  // degenerate (zero-area) triangles never are.
  std::vector<double> cumulative(mesh.triangles.size());
  double total = 0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) cumulative[i] = total += triangle_area(mesh, mesh.triangles[i]);
  if (!(total > 0) || !std::isfinite(total))
    throw InputError("the mesh has no surface area to sample (" + std::to_string(mesh.triangles.size()) +
                     " triangles, all degenerate)");

  const AreaLookup lookup(std::move(cumulative));
  Points samples(count);
  const std::size_t blocks = (count + kSamplesPerBlock - 1) / kSamplesPerBlock;
  for_each_block(blocks, resolve_threads(threads), 1, [&](std::size_t first_block, std::size_t end_block) {
    for (std::size_t b = first_block; b < end_block; ++b) {
      std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                        static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(b >> 32)};
      std::mt19937_64 rng(seq);
      const std::size_t end = std::min(count, (b + 1) * kSamplesPerBlock);
      for (std::size_t i = b * kSamplesPerBlock; i < end; ++i) {
        const auto& t = mesh.triangles[lookup.triangle_at(unit_draw(rng) * total)];
        // Uniform in the triangle: sqrt(r1) spreads points evenly from corner a.
        const double s = std::sqrt(unit_draw(rng)), r2 = unit_draw(rng);
        samples[i] = (1 - s) * mesh.vertices[t[0]] + s * (1 - r2) * mesh.vertices[t[1]] + s * r2 * mesh.vertices[t[2]];
      }
    }
  });
  return samples;
}

}  // namespace touchcloud::scoring
