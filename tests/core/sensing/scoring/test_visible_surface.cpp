// What a press from above can see of a closed object: the top of a cube, not
// its walls (under the top's edge) nor its bottom; what an overhang covers is
// hidden. And the size check that says a mesh is in another unit.
#include <gtest/gtest.h>

#include "touchcloud/error.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "touchcloud/scoring/visible_surface.hpp"

using namespace touchcloud;
using scoring::TriangleMesh;

namespace {

// A closed cube [0, side]^3 as twelve triangles.
TriangleMesh closed_cube(double side) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(side * (i & 1), side * ((i >> 1) & 1), side * ((i >> 2) & 1));
  const std::uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

// Squares at z = 0 (20 mm) and z = 5 (10 mm, over the first's middle): open
// sheets, as a mushroom's cap over its stem's foot.
TriangleMesh cap_over_sheet() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {20, 0, 0}, {20, 20, 0}, {0, 20, 0}, {5, 5, 5}, {15, 5, 5}, {15, 15, 5}, {5, 15, 5}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  return m;
}

}  // namespace

TEST(VisibleFromAbove, OfAClosedCubeOnlyTheTopIsSeen) {
  const TriangleMesh m = closed_cube(10);
  const scoring::Points samples = scoring::sample_surface(m, 60000, 7, 1);
  const scoring::Points seen = scoring::visible_from_above(m, samples);
  // The top is 1/6 of the area; walls and bottom lie under it.
  EXPECT_NEAR(static_cast<double>(seen.size()) / samples.size(), 1.0 / 6, 0.01);
  for (const auto& p : seen) ASSERT_NEAR(p.z(), 10.0, 1e-3) << p.transpose();
}

TEST(VisibleFromAbove, AnOverhangHidesWhatIsUnderIt) {
  const TriangleMesh m = cap_over_sheet();
  const scoring::Points samples = scoring::sample_surface(m, 50000, 3, 1);
  const scoring::Points seen = scoring::visible_from_above(m, samples);
  std::size_t low = 0, high = 0;
  for (const auto& p : seen) {
    if (p.z() > 2.5) {
      ++high;
      continue;
    }
    ++low;
    ASSERT_FALSE(p.x() > 5 + 1e-9 && p.x() < 15 - 1e-9 && p.y() > 5 + 1e-9 && p.y() < 15 - 1e-9) << p.transpose();
  }
  // Area 400 + 100: the cap (1/5 of the samples) all seen, 300 of the 400 below.
  EXPECT_NEAR(static_cast<double>(high) / samples.size(), 0.2, 0.01);
  EXPECT_NEAR(static_cast<double>(low) / samples.size(), 0.6, 0.01);
}

TEST(VisibleFromAbove, GroundTruthKeepsTheDensityAndCountsWhatItLeftOut) {
  scoring::GroundTruthFile file;
  file.file = "cube.obj";
  file.kind = scoring::GroundTruthKind::Mesh;
  file.mesh = closed_cube(10);
  file.area_mm2 = 600;
  scoring::GroundTruthOptions options;
  options.mesh_samples = 60000;
  options.visible = scoring::Visibility::from_above;
  const scoring::GroundTruth gt = scoring::index_ground_truth(file, options);
  EXPECT_EQ(gt.visible, scoring::Visibility::from_above);
  EXPECT_EQ(gt.points.size() + gt.hidden_points, 60000u);
  EXPECT_NEAR(static_cast<double>(gt.hidden_points) / 60000, 5.0 / 6, 0.01);
  EXPECT_DOUBLE_EQ(gt.sample_spacing_mm(), 0.1);  // as drawn: the visible part is as dense as the whole

  scoring::GroundTruthFile cloud;
  cloud.file = "points.pcd";
  cloud.cloud = {{0, 0, 0}};
  EXPECT_THROW(scoring::index_ground_truth(cloud, options), InputError);
}

// A perfect reconstruction of a cube's top covers a sixth of the cube and
// all of what a press from above sees: both shares are reported, in the
// index's order whatever stride the ground truth -> estimate direction takes.
TEST(VisibleFromAbove, VisibleRecallIsTheCoverageOfWhatAPressFromAboveSees) {
  scoring::GroundTruthFile file;
  file.file = "cube.obj";
  file.kind = scoring::GroundTruthKind::Mesh;
  file.mesh = closed_cube(10);
  file.area_mm2 = 600;
  scoring::GroundTruthOptions options;
  options.mesh_samples = 60000;
  options.flag_seen_from_above = true;
  const scoring::GroundTruth gt = scoring::index_ground_truth(file, options);
  ASSERT_EQ(gt.seen_from_above.size(), gt.points.size());
  for (std::size_t i = 0; i < gt.points.size(); ++i) {  // the top seen; walls and bottom not, but at the top's edge
    const double z = gt.points.points()[i].z();
    if (z > 10 - 1e-9 || z < 10 - 1e-3) ASSERT_EQ(gt.seen_from_above[i], z > 10 - 1e-9) << gt.points.points()[i].transpose();
  }

  scoring::Points top;
  for (double x = 0.25; x < 10; x += 0.5)
    for (double y = 0.25; y < 10; y += 0.5) top.emplace_back(x, y, 10);
  for (const std::optional<std::size_t> stride : {std::optional<std::size_t>(), std::optional<std::size_t>(5000)}) {
    scoring::ScoreOptions score;
    score.gt_to_est_samples = stride;
    score.seen_from_above = &gt.seen_from_above;
    const scoring::CloudScore s = scoring::score_estimate(top, gt.points, score);
    // The top (100 of 600 mm^2) and the walls' upper 1.5 mm (60 mm^2), within the threshold of it.
    EXPECT_NEAR(s.recall, 160.0 / 600, 0.01);
    ASSERT_TRUE(s.visible_recall);
    EXPECT_DOUBLE_EQ(*s.visible_recall, 1.0);
    EXPECT_EQ(s.to_score().metrics.back().name, "visible_recall");
  }
  // Without the flags, nothing is claimed about the visible part.
  EXPECT_FALSE(scoring::score_estimate(top, gt.points).visible_recall);
  // Asked for with visible from_above, every point left is seen: no flags.
  options.visible = scoring::Visibility::from_above;
  EXPECT_TRUE(scoring::index_ground_truth(file, options).seen_from_above.empty());
}

TEST(UnitMistake, AMeshInMetresOrMicrometresIsNamedAndMillimetresPass) {
  const auto metres = scoring::unit_mistake(closed_cube(0.02));
  ASSERT_TRUE(metres);
  EXPECT_EQ(*metres, "the object is only 0.02 mm across: is the mesh in metres or centimetres?");
  const auto micrometres = scoring::unit_mistake(closed_cube(20000));
  ASSERT_TRUE(micrometres);
  EXPECT_EQ(*micrometres, "the object is 20000 mm across: is the mesh in micrometres?");
  EXPECT_FALSE(scoring::unit_mistake(closed_cube(20)));
}
