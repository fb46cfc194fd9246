// A cloud written to a full disk is an error naming the file, in every
// encoding (PCL's own writers ignore some failed writes).
#include <gtest/gtest.h>

#include "cloud_files.hpp"
#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

TEST(CloudFileWriting, EveryEncodingRoundTrips) {
  test::TempDir dir;
  const PointCloud cloud = test::grid_cloud(5, 1.0);
  for (const char* name : {"a.pcd", "b.ply"})
    for (bool binary : {true, false}) {
      write_cloud_file(dir / name, cloud, binary);
      EXPECT_EQ(read_cloud_file(dir / name).cloud->size(), cloud.size()) << name << binary;
    }
}

TEST(CloudFileWriting, AFullDiskIsARunErrorNamingTheFile) {
  test::TempDir dir;
  const PointCloud cloud = test::grid_cloud(20, 1.0);
  for (const char* name : {"full.pcd", "full.ply"})
    for (bool binary : {true, false}) {
      fs::remove(dir / name);
      fs::create_symlink("/dev/full", dir / name);  // every write fails with ENOSPC
      try {
        write_cloud_file(dir / name, cloud, binary);
        ADD_FAILURE() << name << (binary ? " binary" : " ascii") << " written to /dev/full without error";
      } catch (const RunError& e) {
        EXPECT_NE(std::string(e.what()).find((dir / name).string()), std::string::npos) << e.what();
      }
    }
}
