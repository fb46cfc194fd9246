// The dedup stage passes its overlap test to the filter: a point lifted 2 mm
// above a kept one, 1 mm aside, is new by Eq. 7's 3D distance and covered
// with overlap: height.
#include <gtest/gtest.h>

#include "stage_harness.hpp"
#include "touchcloud/types/point_cloud.hpp"

using namespace touchcloud;

namespace {
CloudConstPtr one(float x, float z) {
  auto c = std::make_shared<PointCloud>();
  c->push_back(pcl::PointXYZ(x, 0, z));
  return c;
}

std::size_t added_by_second_touch(const std::map<std::string, ParamValue>& params) {
  touchcloud::test::StageHarness stage("dedup", params);
  stage.configure();
  stage.process({{"cloud", one(0, 5)}}, {"added"});
  return stage.process_one<CloudConstPtr>({{"cloud", one(1, 7)}}, "added")->size();
}
}  // namespace

TEST(DedupStage, TheOverlapParameterChoosesTheTest) {
  EXPECT_EQ(added_by_second_touch({}), 1u);
  EXPECT_EQ(added_by_second_touch({{"overlap", std::string("distance")}}), 1u);
  EXPECT_EQ(added_by_second_touch({{"overlap", std::string("height")}}), 0u);
}
