// Nearest detected marker to a pixel, by a nanoflann KD-tree over one view's
// marker centres (a frame has about 2,000: building takes ~0.1 ms).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::markers {

struct Nearest {
  int index = -1;            // into the indexed markers; -1: none within the gate
  double distance_px = 0;
};

class PixelIndex {
 public:
  explicit PixelIndex(const std::vector<Marker>& markers);
  ~PixelIndex();
  PixelIndex(const PixelIndex&) = delete;
  PixelIndex& operator=(const PixelIndex&) = delete;

  // The nearest marker within `gate_px` of `pixel`.
  Nearest nearest(const Eigen::Vector2d& pixel, double gate_px) const;

 private:
  struct Tree;
  std::vector<Eigen::Vector2d> centres_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace touchcloud::markers
