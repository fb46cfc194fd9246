#include "convergence.hpp"

#include <cmath>

namespace touchcloud::chamfer {

int convergence_touches(const std::vector<double>& scores, double tolerance) {
  if (scores.empty()) return 0;
  const double last = scores.back();
  std::size_t first = scores.size() - 1;
  while (first > 0 && std::abs(scores[first - 1] - last) <= tolerance * std::abs(last)) --first;
  return static_cast<int>(first) + 1;
}

}  // namespace touchcloud::chamfer
