// The PLY mesh reader: good meshes in every encoding, and malformed ones
// (each found crashing the former VTK path) as InputError naming the file.
#include <gtest/gtest.h>

#include <cstring>

#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

std::string header(const std::string& format, std::uint64_t vertices, std::uint64_t faces,
                   const std::string& count_type = "uchar", const std::string& coord = "float") {
  return "ply\nformat " + format + " 1.0\ncomment test\nelement vertex " + std::to_string(vertices) +
         "\nproperty " + coord + " x\nproperty " + coord + " y\nproperty " + coord + " z\nelement face " +
         std::to_string(faces) + "\nproperty list " + count_type + " int vertex_indices\nend_header\n";
}

template <class T>
void put(std::string& out, T value, bool big_endian = false) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  out.append(raw, sizeof(T));
}

// A unit square (two triangles, one quad face) in binary.
std::string binary_square(bool big_endian) {
  std::string s = header(big_endian ? "binary_big_endian" : "binary_little_endian", 4, 1, "uchar", "double");
  const double xyz[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0}};
  for (const auto& v : xyz)
    for (double c : v) put(s, c, big_endian);
  put<std::uint8_t>(s, 4);
  for (std::int32_t i : {0, 1, 2, 3}) put(s, i, big_endian);
  return s;
}

std::string read_error(const fs::path& file) {
  try {
    scoring::read_triangle_mesh(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read without error)";
}

class PlyMeshReader : public ::testing::Test {
 protected:
  fs::path write(const std::string& bytes, const std::string& name = "mesh.ply") {
    test::write_file(dir_ / name, bytes);
    return dir_ / name;
  }
  test::TempDir dir_;
};

}  // namespace

TEST_F(PlyMeshReader, ReadsAsciiAndBothBinaryByteOrders) {
  const std::string ascii = header("ascii", 4, 1) + "0 0 0\n2 0 0\n2 3 0\n0 3 0\n4 0 1 2 3\n";
  for (const auto& bytes : {ascii, binary_square(false), binary_square(true)}) {
    const auto mesh = scoring::read_triangle_mesh(write(bytes));
    ASSERT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(2, 3, 0));
    ASSERT_EQ(mesh.triangles.size(), 2u);  // the quad as a fan
    EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
    EXPECT_DOUBLE_EQ(scoring::surface_area_mm2(mesh), 6.0);
  }
}

TEST_F(PlyMeshReader, BinaryDeclaringMoreFacesOrVerticesThanItHoldsIsRefused) {
  std::string more_faces = binary_square(false);
  more_faces.replace(more_faces.find("element face 1"), 14, "element face 9");
  EXPECT_NE(read_error(write(more_faces)).find("the file ends inside face 1"), std::string::npos)
      << read_error(write(more_faces));
  more_faces.replace(more_faces.find("element face 9"), 14, "element face 900");
  EXPECT_NE(read_error(write(more_faces)).find("900 face rows, more than"), std::string::npos)
      << read_error(write(more_faces));
  std::string more_vertices = binary_square(false);
  more_vertices.replace(more_vertices.find("element vertex 4"), 16, "element vertex 400000000");
  const std::string msg = read_error(write(more_vertices));
  EXPECT_NE(msg.find((dir_ / "mesh.ply").string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("400000000 vertex rows"), std::string::npos) << msg;
}

TEST_F(PlyMeshReader, AValidHeaderWithARandomBodyIsRefused) {
  std::string bytes = header("binary_little_endian", 3, 1, "int");
  std::uint32_t state = 12345;
  for (int i = 0; i < 3 * 4 * 3 + 4 + 12; ++i) {
    state = state * 1664525u + 1013904223u;
    bytes.push_back(static_cast<char>(state >> 24));
  }
  const std::string msg = read_error(write(bytes));
  EXPECT_NE(msg.find((dir_ / "mesh.ply").string()), std::string::npos) << msg;
}

TEST_F(PlyMeshReader, AsciiCutInsideItsFacesIsRefused) {
  const std::string bytes = header("ascii", 4, 2) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2";
  const std::string msg = read_error(write(bytes));
  EXPECT_NE(msg.find("mesh.ply: face 1 declares a list of 3 values, more than the rest of the file holds"),
            std::string::npos) << msg;
}

TEST_F(PlyMeshReader, AFaceListOfTwoToTheThirtyOneIsRefusedBeforeAllocating) {
  std::string bytes = header("binary_little_endian", 3, 1, "int");
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(bytes, c);
  put<std::int32_t>(bytes, 2147483647);
  for (std::int32_t i : {0, 1, 2}) put(bytes, i);
  const std::string msg = read_error(write(bytes));
  EXPECT_NE(msg.find("declares a list of 2147483647 values"), std::string::npos) << msg;
}

TEST_F(PlyMeshReader, IndicesPastTheVerticesAndNonFiniteVerticesAreRefused) {
  EXPECT_NE(read_error(write(header("ascii", 3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")).find("uses vertex 7"),
            std::string::npos);
  EXPECT_NE(read_error(write(header("ascii", 3, 1) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n")).find("non-finite"),
            std::string::npos);
  EXPECT_NE(read_error(write(header("ascii", 3, 1) + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n")).find("'x' is not a number"),
            std::string::npos);
}

TEST_F(PlyMeshReader, ABinaryStlDeclaringMoreTrianglesThanItHoldsIsRefused) {
  std::string stl(80, ' ');
  put<std::uint32_t>(stl, 100000);
  for (float f : {0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(stl, f);
  put<std::uint16_t>(stl, 0);
  const std::string msg = read_error(write(stl, "cut.stl"));
  EXPECT_NE(msg.find("cut.stl is not a readable stl mesh: the binary STL declares 100000 triangles"), std::string::npos) << msg;
  // The same file with its true count reads.
  std::memcpy(stl.data() + 80, "\x01\x00\x00\x00", 4);
  EXPECT_EQ(scoring::read_triangle_mesh(write(stl, "one.stl")).triangles.size(), 1u);
}
