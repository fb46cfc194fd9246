// Our PCD reader against files PCL writes in every encoding and point type,
// and against headers it must refuse with the line that is wrong.
#include <gtest/gtest.h>

#include <pcl/io/pcd_io.h>

#include "cloud_files.hpp"
#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

// 7 x 3 organised cloud with colour and normals, so x, y, z are neither the
// only fields nor the first ones in every type.
pcl::PointCloud<pcl::PointXYZRGBNormal> rich_cloud() {
  pcl::PointCloud<pcl::PointXYZRGBNormal> cloud(7, 3);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    auto& p = cloud[i];
    p.x = 0.25f * static_cast<float>(i);
    p.y = -1.5f + static_cast<float>(i % 7);
    p.z = 100.0f + 0.125f * static_cast<float>(i / 7);
    p.r = static_cast<std::uint8_t>(i);
    p.normal_z = 1.0f;
  }
  return cloud;
}

}  // namespace

TEST(PcdFile, ReadsWhatPclWritesInEveryEncoding) {
  test::TempDir dir;
  const auto cloud = rich_cloud();
  ASSERT_EQ(pcl::io::savePCDFileASCII((dir / "ascii.pcd").string(), cloud), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir / "binary.pcd").string(), cloud), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed((dir / "compressed.pcd").string(), cloud), 0);
  for (const char* name : {"ascii.pcd", "binary.pcd", "compressed.pcd"}) {
    const auto read = read_cloud_file(dir / name).cloud;
    ASSERT_EQ(read->size(), cloud.size()) << name;
    EXPECT_EQ(read->height, 1u) << name;  // flattened, in row order
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      EXPECT_FLOAT_EQ((*read)[i].x, cloud[i].x) << name << " point " << i;
      EXPECT_FLOAT_EQ((*read)[i].y, cloud[i].y) << name << " point " << i;
      EXPECT_FLOAT_EQ((*read)[i].z, cloud[i].z) << name << " point " << i;
    }
  }
}

TEST(PcdFile, ReadsDoubleAndIntegerCoordinates) {
  test::TempDir dir;
  const std::string header = "FIELDS i x y z\nSIZE 2 8 4 1\nTYPE U F I I\nWIDTH 2\nDATA binary\n";
  std::string body;
  const auto put = [&](auto v) { body.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(std::uint16_t{7}), put(1.5), put(std::int32_t{-3}), put(std::int8_t{-128});
  put(std::uint16_t{8}), put(-2.25), put(std::int32_t{40}), put(std::int8_t{127});
  test::write_file(dir / "mixed.pcd", header + body);
  const auto cloud = read_cloud_file(dir / "mixed.pcd").cloud;
  ASSERT_EQ(cloud->size(), 2u);
  EXPECT_EQ((*cloud)[0].getVector3fMap(), Eigen::Vector3f(1.5f, -3.0f, -128.0f));
  EXPECT_EQ((*cloud)[1].getVector3fMap(), Eigen::Vector3f(-2.25f, 40.0f, 127.0f));
}

TEST(PcdFile, MalformedHeadersAreRefusedWithTheirLine) {
  test::TempDir dir;
  const std::string xyz = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n";
  const struct {
    const char* name;
    std::string text;
    const char* says;
  } cases[] = {
      {"unknown.pcd", xyz + "WIDTH 1\nCOLOUR red\nDATA ascii\n1 2 3\n", "line 5: unknown header key 'COLOUR'"},
      {"twice.pcd", xyz + "WIDTH 1\nWIDTH 2\nDATA ascii\n1 2 3\n", "line 5: WIDTH is given twice"},
      {"points.pcd", xyz + "WIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n1 2 3\n", "line 7: POINTS 3 is not WIDTH x HEIGHT = 4"},
      {"nowidth.pcd", xyz + "DATA ascii\n1 2 3\n", "line 4: the header has no WIDTH line"},
      {"nodata.pcd", xyz + "WIDTH 1\n", "the header has no DATA line"},
      {"type.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F Q\nWIDTH 1\nDATA ascii\n1 2 3\n", "line 3: TYPE entries are F, I or U, not 'Q'"},
      {"size.pcd", "FIELDS x y z\nSIZE 4 4 3\nTYPE F F F\nWIDTH 1\nDATA ascii\n1 2 3\n", "field 'z' has TYPE F and SIZE 3"},
      {"count.pcd", xyz + "COUNT 1 1 2\nWIDTH 1\nDATA ascii\n1 2 3 4\n", "field 'z' has COUNT 2"},
      {"kind.pcd", xyz + "WIDTH 1\nDATA text\n1 2 3\n", "line 5: DATA must be ascii, binary or binary_compressed, not 'text'"},
      {"short.pcd", xyz + "WIDTH 1\nDATA binary_compressed\n\x05", "its compressed data is truncated"},
      {"corrupt.pcd", xyz + "WIDTH 1\nDATA binary_compressed\n" + std::string("\x04\0\0\0\x0c\0\0\0\xff\xff\xff\xff", 12),
       "its compressed data is corrupt"},
      {"notpcd.pcd", "hello world\n", "(no valid PCD header: line 1)"},
  };
  for (const auto& c : cases) {
    test::write_file(dir / c.name, c.text);
    const std::string msg = test::cloud_read_error(dir / c.name);
    EXPECT_NE(msg.find((dir / c.name).string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.says), std::string::npos) << c.name << ": " << msg;
  }
}
