// Ground truth and estimates from files: meshes (STL, OBJ, PLY with faces)
// are sampled, clouds (PCD, PLY without faces) taken as they are, and broken
// files are refused with their name in the message.
#include <gtest/gtest.h>

#include "cloud_files.hpp"
#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

using namespace touchcloud;
using touchcloud::test::write_file;

namespace {

// The unit square at z = 0, as two triangles, in three mesh formats.
const char* kSquareStl =
    "solid square\n"
    "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 10 0 0\n  vertex 10 10 0\n endloop\nendfacet\n"
    "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 10 10 0\n  vertex 0 10 0\n endloop\nendfacet\n"
    "endsolid square\n";
const char* kSquareObj = "# a 10 mm square as one quad\nv 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3 4\n";
const char* kSquarePly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n10 0 0\n10 10 0\n0 10 0\n3 0 1 2\n3 0 2 3\n";
const char* kCloudPly =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
    "0 0 0\n1 0 0\n0 2 0\n";

void expect_sampled_square(const scoring::GroundTruth& gt) {
  EXPECT_EQ(gt.kind, scoring::GroundTruthKind::Mesh);
  EXPECT_DOUBLE_EQ(gt.area_mm2, 100.0);
  EXPECT_EQ(gt.triangles, 2u);
  ASSERT_EQ(gt.points.size(), 5000u);
  EXPECT_DOUBLE_EQ(gt.sample_spacing_mm(), std::sqrt(100.0 / 5000));
  for (const auto& p : gt.points.points()) {
    EXPECT_EQ(p.z(), 0.0);
    EXPECT_TRUE(p.x() >= 0 && p.x() <= 10 && p.y() >= 0 && p.y() <= 10) << p.transpose();
  }
}


}  // namespace

TEST(GroundTruthFiles, MeshesInEachFormatAreSampled) {
  test::TempDir dir;
  scoring::GroundTruthOptions o;
  o.mesh_samples = 5000;
  for (const auto& [name, text] : {std::pair{"square.stl", kSquareStl}, std::pair{"square.obj", kSquareObj},
                                   std::pair{"square.ply", kSquarePly}}) {
    SCOPED_TRACE(name);
    write_file(dir / name, text);
    EXPECT_TRUE(scoring::is_mesh_file(dir / name));
    expect_sampled_square(scoring::load_ground_truth(dir / name, o));
  }
}

TEST(GroundTruthFiles, SameSeedSameSamples) {
  test::TempDir dir;
  write_file(dir / "square.obj", kSquareObj);
  scoring::GroundTruthOptions o;
  o.mesh_samples = 1000;
  o.seed = 5;
  const auto a = scoring::load_ground_truth(dir / "square.obj", o);
  const auto b = scoring::load_ground_truth(dir / "square.obj", o);
  o.seed = 6;
  const auto c = scoring::load_ground_truth(dir / "square.obj", o);
  EXPECT_EQ(a.points.points(), b.points.points());
  EXPECT_NE(a.points.points(), c.points.points());
}

// Reading checks the file and measures the mesh; the samples come only with
// the index, and are those a one-step load gives.
TEST(GroundTruthFiles, ReadingLeavesTheSamplingToTheIndex) {
  test::TempDir dir;
  write_file(dir / "square.obj", kSquareObj);
  scoring::GroundTruthOptions o;
  o.mesh_samples = 1000;
  scoring::GroundTruthFile file = scoring::read_ground_truth(dir / "square.obj", o);
  EXPECT_EQ(file.kind, scoring::GroundTruthKind::Mesh);
  EXPECT_EQ(file.mesh.triangles.size(), 2u);
  EXPECT_DOUBLE_EQ(file.area_mm2, 100.0);
  EXPECT_TRUE(file.cloud.empty());
  const auto indexed = scoring::index_ground_truth(std::move(file), o);
  EXPECT_EQ(indexed.points.size(), 1000u);
  EXPECT_EQ(indexed.points.points(), scoring::load_ground_truth(dir / "square.obj", o).points.points());
  EXPECT_DOUBLE_EQ(indexed.area_mm2, 100.0);
}

TEST(GroundTruthFiles, CloudsAreTakenAsTheyAre) {
  test::TempDir dir;
  write_file(dir / "cloud.ply", kCloudPly);
  EXPECT_FALSE(scoring::is_mesh_file(dir / "cloud.ply"));
  const auto ply = scoring::load_ground_truth(dir / "cloud.ply");
  EXPECT_EQ(ply.kind, scoring::GroundTruthKind::Cloud);
  EXPECT_EQ(ply.points.points(), (scoring::Points{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}}));
  EXPECT_EQ(ply.sample_spacing_mm(), 0.0);

  test::save_pcd(dir / "grid.pcd", test::grid_cloud(3, 2.0));
  const auto pcd = scoring::load_ground_truth(dir / "grid.pcd");
  EXPECT_EQ(pcd.kind, scoring::GroundTruthKind::Cloud);
  ASSERT_EQ(pcd.points.size(), 9u);
  EXPECT_EQ(pcd.points.points()[8], Eigen::Vector3d(4, 4, 0));
}

TEST(GroundTruthFiles, BrokenMeshesAreRefusedByName) {
  test::TempDir dir;
  write_file(dir / "garbage.stl", "this is not an STL file\n");
  write_file(dir / "empty.obj", "");
  write_file(dir / "points_only.obj", "v 0 0 0\nv 1 0 0\n");
  write_file(dir / "bad_index.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  write_file(dir / "flat.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n");
  for (const char* name : {"garbage.stl", "empty.obj", "points_only.obj", "bad_index.ply", "flat.obj", "missing.stl"}) {
    const std::string m = test::input_error_of([&] { scoring::load_ground_truth(dir / name); });
    EXPECT_NE(m.find(name), std::string::npos) << name << ": " << m;
  }
  EXPECT_NE(test::input_error_of([&] { scoring::load_ground_truth(dir / "flat.obj"); }).find("no surface area"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { scoring::read_ground_truth(dir / "flat.obj"); }).find("flat.obj: the mesh has no surface area"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([&] { scoring::load_ground_truth(dir / "points_only.obj"); }).find("no triangles"),
            std::string::npos);
}

TEST(GroundTruthFiles, EstimatesMustHoldFinitePoints) {
  test::TempDir dir;
  write_file(dir / "empty.pcd", "");
  EXPECT_NE(test::input_error_of([&] { scoring::read_estimate(dir / "empty.pcd"); }).find("empty.pcd"), std::string::npos);
  PointCloud with_nan = test::grid_cloud(2, 1.0);
  with_nan.push_back(pcl::PointXYZ(std::nanf(""), 0, 0));
  test::save_pcd(dir / "nan.pcd", with_nan);
  EXPECT_THROW(scoring::read_estimate(dir / "nan.pcd"), InputError);
  const auto kept = scoring::read_estimate(dir / "nan.pcd", NonFinitePoints::Drop);
  EXPECT_EQ(kept.points.size(), 4u);
  EXPECT_EQ(kept.dropped_nonfinite, 1u);
}
