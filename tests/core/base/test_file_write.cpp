// write_file: a failed write (here every write: /dev/full) is a RunError
// naming the file, never a short file and a success.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/file_write.hpp"

using namespace touchcloud;

TEST(FileWrite, WritesAndAFullDiskIsARunErrorNamingTheFile) {
  test::TempDir dir;
  write_file(dir / "a.txt", "hello\n");
  EXPECT_EQ(test::read_file(dir / "a.txt"), "hello\n");
  try {
    write_file("/dev/full", std::string(100000, 'x'));
    FAIL() << "a write to /dev/full succeeded";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full: No space left on device"), std::string::npos) << e.what();
  }
}
