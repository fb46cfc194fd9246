// Cloud files that PCL alone would read wrongly or die on: a non-numeric
// ASCII value, counts far past the file's size.
#include <gtest/gtest.h>

#include "cloud_files.hpp"
#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

std::string pcd_header(const std::string& data, std::uint64_t width, std::uint64_t points) {
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " + std::to_string(width) +
         "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(points) + "\nDATA " + data + "\n";
}

}  // namespace

TEST(CloudFileReading, ANonNumericAsciiPcdLineIsAnErrorWithItsLine) {
  test::TempDir dir;
  test::write_file(dir / "a.pcd", pcd_header("ascii", 3, 3) + "0 0 0\nhello world !\n1 1 1\n");
  const std::string msg = test::cloud_read_error(dir / "a.pcd");
  EXPECT_NE(msg.find("a.pcd:13: 'hello' is not a number (point 1)"), std::string::npos) << msg;
  test::write_file(dir / "b.pcd", pcd_header("ascii", 3, 3) + "10.0 10.0 10.0\n1.5 1.5\n1.0 1.0 1.0\n");
  EXPECT_NE(test::cloud_read_error(dir / "b.pcd").find("point 1 has 2 values"), std::string::npos) << test::cloud_read_error(dir / "b.pcd");
  // The good file reads.
  test::write_file(dir / "c.pcd", pcd_header("ascii", 3, 3) + "0 0 0\n1e-3 2 -3\n1 1 1\n");
  EXPECT_EQ(read_cloud_file(dir / "c.pcd").cloud->size(), 3u);
}

TEST(CloudFileReading, AbsurdPointCountsAreBadInputNotAnAllocationFailure) {
  test::TempDir dir;
  test::write_file(dir / "binary.pcd", pcd_header("binary", 4000000000u, 4000000000u) + std::string(12, '\0'));
  test::write_file(dir / "ascii.pcd", pcd_header("ascii", 4000000000u, 4000000000u) + "0 0 0\n");
  test::write_file(dir / "cloud.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                                      "property float x\nproperty float y\nproperty float z\nend_header\n" +
                                          std::string(12, '\0'));
  for (const char* name : {"binary.pcd", "ascii.pcd", "cloud.ply"}) {
    const std::string msg = test::cloud_read_error(dir / name);
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
    EXPECT_NE(msg.find("4000000000"), std::string::npos) << msg;
  }
}
