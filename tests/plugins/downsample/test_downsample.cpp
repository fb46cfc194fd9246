// downsample: voxel centroids on a hand-checkable grid, exact random counts,
// seeded reproducibility, and a refusal where PCL would silently do nothing.
#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"

using namespace touchcloud;

class Downsample : public touchcloud::test::PipelineFixture {
 protected:
  PointCloud thin(const std::string& params, std::uint64_t seed = 0) {
    Pipeline p = load("stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: in.pcd}\n"
                      "  - id: thin\n    plugin: downsample\n    params: " + params +
                      "\n    inputs: {cloud: read.cloud}\n"
                      "  - id: write\n    plugin: cloud_writer\n    params: {path: out.pcd}\n"
                      "    inputs: {cloud: thin.cloud}\n");
    RunOptions o;
    o.quiet = true;
    o.seed = seed;
    o.out_dir = dir_ / ("out" + std::to_string(runs_++));
    run_pipeline(p, o);
    return touchcloud::test::load_cloud(o.out_dir / "out.pcd");
  }
  int runs_ = 0;
};

TEST_F(Downsample, VoxelGridKeepsOneCentroidPerOccupiedVoxel) {
  // 10 x 10 points 1 mm apart at 0..9 mm; 2 mm voxels pair them up: 5 x 5
  // voxels, each the centroid of a 2 x 2 block (x.5 coordinates).
  touchcloud::test::save_pcd(dir_ / "in.pcd", touchcloud::test::grid_cloud(10, 1.0));
  const PointCloud out = thin("{method: voxel, leaf_size_mm: 2.0}");
  ASSERT_EQ(out.size(), 25u);
  for (const auto& p : out) {
    EXPECT_NEAR(std::fmod(p.x, 2.0), 0.5, 1e-5);
    EXPECT_NEAR(std::fmod(p.y, 2.0), 0.5, 1e-5);
  }
}

TEST_F(Downsample, RandomKeepsTheRequestedShareReproducibly) {
  touchcloud::test::save_pcd(dir_ / "in.pcd", touchcloud::test::grid_cloud(20, 1.0));
  const PointCloud a = thin("{method: random, keep_ratio: 0.25}", 3);
  const PointCloud b = thin("{method: random, keep_ratio: 0.25}", 3);
  const PointCloud c = thin("{method: random, keep_ratio: 0.25}", 4);
  ASSERT_EQ(a.size(), 100u);
  ASSERT_EQ(b.size(), a.size());
  bool same_ab = true, same_ac = true;
  for (std::size_t i = 0; i < a.size(); ++i) {
    same_ab = same_ab && a[i].x == b[i].x && a[i].y == b[i].y;
    same_ac = same_ac && a[i].x == c[i].x && a[i].y == c[i].y;
  }
  EXPECT_TRUE(same_ab) << "same seed, same points";
  EXPECT_FALSE(same_ac) << "another seed, other points";
}

TEST_F(Downsample, RefusesALeafTooSmallForPclToIndex) {
  PointCloud far;
  far.push_back(pcl::PointXYZ(0, 0, 0));
  far.push_back(pcl::PointXYZ(1e4f, 1e4f, 1e4f));
  touchcloud::test::save_pcd(dir_ / "in.pcd", far);
  try {
    thin("{method: voxel, leaf_size_mm: 0.01}");
    FAIL() << "PCL would have returned the input unchanged";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("leaf_size_mm"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("more than PCL's voxel grid can index"), std::string::npos) << e.what();
  }
}

// The message keeps the leaf's digits (std::to_string gives "0.000000").
TEST_F(Downsample, ATinyLeafIsNamedWithItsDigits) {
  touchcloud::test::save_pcd(dir_ / "in.pcd", touchcloud::test::grid_cloud(3, 1.0));
  try {
    thin("{method: voxel, leaf_size_mm: 1e-300}");
    FAIL() << "a grid of 10^600 cells";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a 1e-300 mm grid over this cloud's extent needs inf cells"), std::string::npos)
        << e.what();
  }
}

// A ratio that keeps nothing is refused naming the ratio (not at the writer,
// as an empty cloud), at validation when it is 0, at the stage when the
// cloud is too small for it.
TEST_F(Downsample, ARatioThatKeepsNoPointIsRefusedNamingTheRatio) {
  touchcloud::test::save_pcd(dir_ / "in.pcd", touchcloud::test::grid_cloud(3, 1.0));
  const auto d = errors("stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: in.pcd}\n"
                        "  - id: thin\n    plugin: downsample\n    params: {method: random, keep_ratio: 0}\n"
                        "    inputs: {cloud: read.cloud}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(touchcloud::test::mentions(d[0], "parameter 'keep_ratio': value 0 is out of range: must be in (0, 1]"))
      << d[0].str();
  EXPECT_EQ(d[0].where.line, 7);
  try {
    thin("{method: random, keep_ratio: 0.01}");
    FAIL() << "1% of 9 points";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("keep_ratio"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("0.01 of this cloud's 9 points keeps none"), std::string::npos) << e.what();
  }
}
