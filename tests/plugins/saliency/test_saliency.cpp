// Eq. 4 on hand-made displacements, and the frame change to the base.
#include <gtest/gtest.h>

#include "salient_points.hpp"

using namespace touchcloud;
using namespace touchcloud::saliency;

TEST(Saliency, KeepsMarkersAboveAlphaTimesTheMaximum) {
  // max 5 mm, alpha 0.2 -> threshold 1 mm; 1.0 itself is not above it.
  const std::vector<double> d = {0.0, 0.5, 1.0, 1.01, 3.0, 5.0, 0.99};
  EXPECT_EQ(salient_markers(d, 0.2, SalientSelection::All), (std::vector<std::size_t>{3, 4, 5}));
  EXPECT_EQ(salient_markers(d, 0.0, SalientSelection::All), (std::vector<std::size_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(salient_markers(d, 1.0, SalientSelection::All), (std::vector<std::size_t>{}));
}

TEST(Saliency, DeepestKeepsTheSingleMostDisplacedMarker) {
  EXPECT_EQ(salient_markers({0.1, 2.0, 0.3}, 0.2, SalientSelection::Deepest), (std::vector<std::size_t>{1}));
}

TEST(Saliency, NoMotionMeansNoContact) {
  EXPECT_TRUE(salient_markers({0.0, 0.0}, 0.2, SalientSelection::All).empty());
  EXPECT_TRUE(salient_markers({}, 0.2, SalientSelection::All).empty());
}

TEST(Saliency, CloudIsMappedIntoTheBaseFrame) {
  TactileCloud t;
  auto points = std::make_shared<PointCloud>();
  points->push_back(pcl::PointXYZ(1, 2, 30));
  points->push_back(pcl::PointXYZ(0, 0, 32.5f));
  t.points = points;
  t.displacement_mm = {2.0, 0.1};
  // The sensor faces down at (100, 50, 80) in the base frame: 180 deg about x.
  t.pose.base_from_sensor = Eigen::Translation3d(100, 50, 80) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
  const auto idx = salient_markers(t.displacement_mm, 0.2, SalientSelection::All);
  const CloudPtr base = salient_cloud(t, idx, Frame::Base);
  ASSERT_EQ(base->size(), 1u);
  EXPECT_NEAR(base->at(0).x, 101, 1e-5);
  EXPECT_NEAR(base->at(0).y, 48, 1e-5);
  EXPECT_NEAR(base->at(0).z, 50, 1e-5);
  const CloudPtr sensor = salient_cloud(t, idx, Frame::Sensor);
  EXPECT_EQ(sensor->at(0).z, 30.0f);
}
