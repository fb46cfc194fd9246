// Point-cloud de-duplication across touches (Eq. 7 of the GelStereo Palm 2.0
// paper): a new point is kept only when its nearest neighbour among the
// points kept from earlier touches is farther than the threshold (the mean
// marker spacing, 1.8 mm). Points of one touch are not compared with each
// other: they are distinct markers, about one spacing apart by construction.
#pragma once

#include <pcl/kdtree/kdtree_flann.h>

#include "touchcloud/types/point_cloud.hpp"

namespace touchcloud::dedup {

class OverlapFilter {
 public:
  explicit OverlapFilter(double threshold_mm) : threshold_mm_(threshold_mm) {}

  // Adds the points of `touch` that do not overlap what is kept; returns them.
  CloudPtr add(const PointCloud& touch);
  // Adds every point (the w/o PCP baseline).
  CloudPtr add_all(const PointCloud& touch);

  const PointCloud& kept() const { return kept_; }

 private:
  double threshold_mm_;
  PointCloud kept_;
  pcl::KdTreeFLANN<pcl::PointXYZ> index_;  // over kept_, rebuilt after each touch
};

}  // namespace touchcloud::dedup
