// STL (ASCII and binary) and OBJ meshes read by our readers: hand-made
// files with known vertices, triangles and area.
#include <gtest/gtest.h>

#include <cstring>

#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

using namespace touchcloud;

TEST(StlObjMeshReaders, AsciiAndBinaryStlGiveTheSameTriangles) {
  test::TempDir dir;
  test::write_file(dir / "a.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 2 0 0\nvertex 0 3 0\n"
                                  "endloop\nendfacet\nendsolid t\n");
  std::string binary = "solid but binary" + std::string(64, ' ');
  const std::uint32_t one = 1;
  binary.append(reinterpret_cast<const char*>(&one), 4);
  const float tri[12] = {0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3, 0};
  binary.append(reinterpret_cast<const char*>(tri), sizeof tri);
  binary.append(2, '\0');
  test::write_file(dir / "b.stl", binary);
  for (const char* name : {"a.stl", "b.stl"}) {
    const auto mesh = scoring::read_triangle_mesh(dir / name);
    ASSERT_EQ(mesh.triangles.size(), 1u) << name;
    EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(2, 0, 0)) << name;
    EXPECT_DOUBLE_EQ(scoring::surface_area_mm2(mesh), 3.0) << name;
  }
}

TEST(StlObjMeshReaders, ObjCornerFormsAndNegativeIndices) {
  test::TempDir dir;
  test::write_file(dir / "q.obj", "# quad\nv 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nvt 0 0\nvn 0 0 1\n"
                                  "f 1/1/1 2//1 3/1\nf -4 -2 -1\n");
  const auto mesh = scoring::read_triangle_mesh(dir / "q.obj");
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_DOUBLE_EQ(scoring::surface_area_mm2(mesh), 6.0);
  test::write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  try {
    scoring::read_triangle_mesh(dir / "bad.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.obj:3: not a readable obj mesh: face uses vertex 3 but 2 vertices"),
              std::string::npos) << e.what();
  }
}
