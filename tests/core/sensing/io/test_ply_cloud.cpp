// The PLY cloud reader on the layouts other tools write (Open3D's double
// x, y, z with normals and colours, PCL's float cloud with its camera
// element), every numeric type in any order, all three encodings, and on
// files it must refuse with the file and the row named.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <functional>

#include <pcl/io/ply_io.h>

#include "cloud_files.hpp"
#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

// One property of element 'vertex': its PLY type and a value per row (a
// list property holds `list_length` copies of the row's value).
struct Column {
  std::string type, name;
  std::function<double(int)> value;
  int list_length = -1;  // -1: a scalar
};

enum class Encoding { Ascii, Little, Big };

void put(std::string& out, const std::string& type, double v, Encoding enc) {
  if (enc == Encoding::Ascii) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g ", v);
    out += text;
    return;
  }
  unsigned char raw[8];
  std::size_t size = 0;
  const auto store = [&](auto x) {
    size = sizeof x;
    std::memcpy(raw, &x, size);
  };
  if (type == "char" || type == "int8") store(static_cast<std::int8_t>(v));
  else if (type == "uchar" || type == "uint8") store(static_cast<std::uint8_t>(v));
  else if (type == "short" || type == "int16") store(static_cast<std::int16_t>(v));
  else if (type == "ushort" || type == "uint16") store(static_cast<std::uint16_t>(v));
  else if (type == "int" || type == "int32") store(static_cast<std::int32_t>(v));
  else if (type == "uint" || type == "uint32") store(static_cast<std::uint32_t>(v));
  else if (type == "float" || type == "float32") store(static_cast<float>(v));
  else store(v);
  if ((enc == Encoding::Big) == (std::endian::native == std::endian::little)) std::reverse(raw, raw + size);
  out.append(reinterpret_cast<const char*>(raw), size);
}

std::string ply_file(const std::vector<Column>& columns, int rows, Encoding enc, const std::string& before = "",
                     const std::string& after = "") {
  std::string text = std::string("ply\nformat ") +
                     (enc == Encoding::Ascii ? "ascii" : enc == Encoding::Little ? "binary_little_endian" : "binary_big_endian") +
                     " 1.0\ncomment made by a test\n" + before + "element vertex " + std::to_string(rows) + "\n";
  for (const auto& c : columns)
    text += c.list_length < 0 ? "property " + c.type + " " + c.name + "\n"
                              : "property list uchar " + c.type + " " + c.name + "\n";
  text += after + "end_header\n";
  return text;
}

std::string ply_rows(const std::vector<Column>& columns, int rows, Encoding enc) {
  std::string body;
  for (int r = 0; r < rows; ++r) {
    for (const auto& c : columns) {
      if (c.list_length >= 0) {
        put(body, "uchar", c.list_length, enc);
        for (int i = 0; i < c.list_length; ++i) put(body, c.type, c.value(r), enc);
      } else {
        put(body, c.type, c.value(r), enc);
      }
    }
    if (enc == Encoding::Ascii) body += "\n";
  }
  return body;
}

const char* name_of(Encoding e) { return e == Encoding::Ascii ? "ascii" : e == Encoding::Little ? "little" : "big"; }

}  // namespace

// Open3D's default: double x, y, z, double normals, uchar colours.
TEST(PlyCloud, ReadsDoubleCoordinatesWithNormalsAndColoursExactly) {
  test::TempDir dir;
  const auto x = [](int r) { return 10.123456789012345 + r * 3.3; };
  const auto y = [](int r) { return -7.25e-3 * (r + 1); };
  const auto z = [](int r) { return 1e5 + r / 3.0; };
  const std::vector<Column> columns = {{"double", "x", x},      {"double", "y", y},      {"double", "z", z},
                                       {"double", "nx", y},     {"double", "ny", x},     {"double", "nz", z},
                                       {"uchar", "red", [](int r) { return r; }},
                                       {"uchar", "green", [](int) { return 255; }}, {"uchar", "blue", [](int) { return 0; }}};
  for (Encoding enc : {Encoding::Little, Encoding::Ascii, Encoding::Big}) {
    const fs::path file = dir / (std::string(name_of(enc)) + ".ply");
    test::write_file(file, ply_file(columns, 50, enc) + ply_rows(columns, 50, enc));
    const auto cloud = read_cloud_file(file).cloud;
    ASSERT_EQ(cloud->size(), 50u) << file;
    for (int r = 0; r < 50; ++r) {
      EXPECT_EQ((*cloud)[r].x, static_cast<float>(x(r))) << file << " row " << r;
      EXPECT_EQ((*cloud)[r].y, static_cast<float>(y(r))) << file << " row " << r;
      EXPECT_EQ((*cloud)[r].z, static_cast<float>(z(r))) << file << " row " << r;
    }
  }
}

// Every type under both of its names, x, y and z in any order among other
// properties and lists, and elements before and after 'vertex'.
TEST(PlyCloud, ReadsEveryNumericTypeInAnyOrder) {
  test::TempDir dir;
  const std::vector<std::pair<std::string, double>> types = {
      {"char", -100},  {"int8", 100},     {"uchar", 200},        {"uint8", 255},     {"short", -30000},
      {"int16", 30000}, {"ushort", 60000}, {"uint16", 1},        {"int", -2000000000}, {"int32", 7},
      {"uint", 4000000000.0}, {"uint32", 3}, {"float", 0.1},     {"float32", -2.5},  {"double", 0.1},
      {"float64", 1e-300}};
  const std::string before = "element material 2\nproperty uchar shininess\nproperty list uchar float tint\n";
  const std::string before_rows_ascii = "1 2 0.5 0.5\n3 0\n";
  for (const auto& [type, value] : types)
    for (Encoding enc : {Encoding::Ascii, Encoding::Little, Encoding::Big}) {
      const double v = value;
      const std::vector<Column> columns = {{"float", "intensity", [](int) { return 9; }},
                                           {type, "z", [v](int) { return v; }},
                                           {"int", "ids", [](int r) { return r; }, 2},
                                           {"double", "y", [](int r) { return r + 0.5; }},
                                           {type, "x", [v](int) { return v; }},
                                           {"ushort", "label", [](int) { return 4; }}};
      std::string material = before_rows_ascii;
      if (enc != Encoding::Ascii) {
        material.clear();
        put(material, "uchar", 1, enc), put(material, "uchar", 2, enc), put(material, "float", 0.5, enc),
            put(material, "float", 0.5, enc);
        put(material, "uchar", 3, enc), put(material, "uchar", 0, enc);
      }
      std::string face;
      for (int corner : {3, 0, 1, 2}) put(face, corner == 3 ? "uchar" : "int", corner, enc);
      const fs::path file = dir / (type + "_" + name_of(enc) + ".ply");
      test::write_file(file, ply_file(columns, 3, enc, before, "element face 1\nproperty list uchar int vertex_indices\n") +
                                 material + ply_rows(columns, 3, enc) + face);
      const auto cloud = read_cloud_file(file).cloud;
      ASSERT_EQ(cloud->size(), 3u) << file;
      const float expected = static_cast<float>(v);
      for (int r = 0; r < 3; ++r) {
        EXPECT_EQ((*cloud)[r].x, expected) << file << " row " << r;
        EXPECT_EQ((*cloud)[r].y, static_cast<float>(r + 0.5)) << file << " row " << r;
        EXPECT_EQ((*cloud)[r].z, expected) << file << " row " << r;
      }
    }
}

// PCL's writer: float x, y, z and an element 'camera' after the points.
TEST(PlyCloud, ReadsWhatPclWrites) {
  test::TempDir dir;
  pcl::PointCloud<pcl::PointXYZRGBNormal> written(9, 2);
  for (std::size_t i = 0; i < written.size(); ++i) {
    written[i].x = 0.1f * static_cast<float>(i);
    written[i].y = -3.7f + static_cast<float>(i);
    written[i].z = 1000.3f;
    written[i].r = 7;
  }
  ASSERT_EQ(pcl::io::savePLYFileBinary((dir / "binary.ply").string(), written), 0);
  ASSERT_EQ(pcl::io::savePLYFileASCII((dir / "ascii.ply").string(), written), 0);
  for (const char* name : {"binary.ply", "ascii.ply"}) {
    const auto cloud = read_cloud_file(dir / name).cloud;
    ASSERT_EQ(cloud->size(), written.size()) << name;
    for (std::size_t i = 0; i < written.size(); ++i) {
      // PCL's ASCII writer keeps 8 significant digits: float's round trip needs 9.
      const float tolerance = std::string(name) == "ascii.ply" ? 1e-7f * std::abs(written[i].z) : 0.0f;
      EXPECT_NEAR((*cloud)[i].x, written[i].x, tolerance) << name << " point " << i;
      EXPECT_NEAR((*cloud)[i].y, written[i].y, tolerance) << name << " point " << i;
      EXPECT_NEAR((*cloud)[i].z, written[i].z, tolerance) << name << " point " << i;
    }
  }
}

TEST(PlyCloud, RefusesWhatIsNoCloudNamingTheFileAndRow) {
  test::TempDir dir;
  const auto one = [](int r) { return r; };
  const std::vector<Column> xyz = {{"double", "x", one}, {"double", "y", one}, {"double", "z", one}};
  // Truncated inside row 2.
  std::string whole = ply_file(xyz, 3, Encoding::Little) + ply_rows(xyz, 3, Encoding::Little);
  test::write_file(dir / "cut.ply", whole.substr(0, whole.size() - 4));
  std::string msg = test::cloud_read_error(dir / "cut.ply");
  EXPECT_NE(msg.find("cut.ply"), std::string::npos) << msg;
  EXPECT_NE(msg.find("more than"), std::string::npos) << msg;  // the header's count against the size
  // A value that is no number (ASCII): the row is named.
  test::write_file(dir / "word.ply", ply_file(xyz, 3, Encoding::Ascii) + "0 0 0\n1 one 1\n2 2 2\n");
  msg = test::cloud_read_error(dir / "word.ply");
  EXPECT_NE(msg.find("word.ply: vertex 1: 'one' is not a number"), std::string::npos) << msg;
  // No z; x a list; no vertex element.
  test::write_file(dir / "no_z.ply", ply_file({xyz[0], xyz[1]}, 1, Encoding::Ascii) + "0 0\n");
  EXPECT_NE(test::cloud_read_error(dir / "no_z.ply").find("no 'z' property"), std::string::npos);
  test::write_file(dir / "list_x.ply", ply_file({{"float", "x", one, 1}, xyz[1], xyz[2]}, 1, Encoding::Ascii) + "1 0 0 0\n");
  EXPECT_NE(test::cloud_read_error(dir / "list_x.ply").find("'x' is a list"), std::string::npos);
  test::write_file(dir / "faces.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n");
  EXPECT_NE(test::cloud_read_error(dir / "faces.ply").find("no 'vertex' element"), std::string::npos);
  test::write_file(dir / "none.ply", ply_file(xyz, 0, Encoding::Ascii));
  EXPECT_NE(test::cloud_read_error(dir / "none.ply").find("contains no points"), std::string::npos);
  // A list longer than the file.
  test::write_file(dir / "long_list.ply", ply_file({xyz[0], xyz[1], xyz[2], {"int", "ids", one, 0}}, 1, Encoding::Little) +
                                              std::string(24, '\0') + "\xff" + std::string(8, '\0'));
  msg = test::cloud_read_error(dir / "long_list.ply");
  EXPECT_NE(msg.find("vertex 0 declares a list of 255 values"), std::string::npos) << msg;
}
