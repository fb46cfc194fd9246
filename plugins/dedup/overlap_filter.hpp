// Point-cloud de-duplication across touches (Eq. 7 of the GelStereo Palm 2.0
// paper): a new point is kept only when its nearest neighbour among the
// points kept from earlier touches is farther than the threshold (the mean
// marker spacing, 1.8 mm). Points of one touch are not compared with each
// other: they are distinct markers, about one spacing apart by construction.
#pragma once

#include <pcl/kdtree/kdtree_flann.h>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::dedup {

// How a new point overlaps a kept one.
enum class OverlapTest {
  distance,  // Eq. 7: within the threshold in 3D
  // A height field whose errors lie above the surface (the gel's elastic
  // spread lifts markers beside a contact, it never sinks them): a kept point
  // within the threshold in (x, y) covers a new one unless the new one lies
  // more than the threshold below it, which is better evidence of the surface.
  height,
};

class OverlapFilter {
 public:
  explicit OverlapFilter(double threshold_mm, OverlapTest overlap = OverlapTest::distance)
      : threshold_mm_(threshold_mm), overlap_(overlap) {}

  // Adds the points of `touch` that do not overlap what is kept; returns them.
  CloudPtr add(const PointCloud& touch);
  // Adds every point (the w/o PCP baseline).
  CloudPtr add_all(const PointCloud& touch);

  const PointCloud& kept() const { return kept_; }

 private:
  bool overlaps(const pcl::PointXYZ& p);

  double threshold_mm_;
  OverlapTest overlap_;
  PointCloud kept_;
  // Over kept_ (height: over its (x, y) with z = 0), rebuilt after each touch.
  pcl::KdTreeFLANN<pcl::PointXYZ> index_;
  std::vector<int> found_;
  std::vector<float> squared_;
};

}  // namespace touchcloud::dedup
