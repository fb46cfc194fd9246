// Every input the fuzzers (fuzz/) found crashing a reader, read again: no
// crash, and a clear InputError for the corrupt ones. They also seed the fuzzers.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/io/image_file.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {
const fs::path kCorpus = test::source_dir() / "fuzz/corpus";

template <class F>
std::string input_error(const fs::path& file, F&& read) {
  return test::input_error_of([&] { read(file); });
}
}  // namespace

// PCL's PCD header parser threw std::out_of_range (std::terminate in the CLI's stages).
TEST(FuzzRegressions, PcdHeaderThatThrowsOutOfRange) {
  const fs::path file = kCorpus / "fuzz_pcd/crash-out-of-range-header.pcd";
  const std::string msg = input_error(file, [](const fs::path& f) { read_cloud_file(f); });
  EXPECT_NE(msg.find(file.string() + " is not a readable pcd point cloud"), std::string::npos) << msg;
}

// VTK's ASCII STL reader took more than 2 GB on this 122-byte file.
TEST(FuzzRegressions, AsciiStlThatExhaustedMemory) {
  const fs::path file = kCorpus / "fuzz_stl/oom-ascii.stl";
  const std::string msg = input_error(file, [](const fs::path& f) { scoring::read_triangle_mesh(f); });
  EXPECT_NE(msg.find(file.string() + " is not a readable stl mesh"), std::string::npos) << msg;
}

// PCL's vtk2mesh overflowed a heap buffer on this file; its line 'f1 1 //2//1
// 3//1' is no face ('f1' is an unknown statement, ignored as OBJ readers
// do), so the mesh is the one triangle 'f 1 3 4'.
TEST(FuzzRegressions, ObjThatOverflowedAHeapBuffer) {
  const auto mesh = scoring::read_triangle_mesh(kCorpus / "fuzz_obj/crash-mixed-corners.obj");
  EXPECT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

// A TYPE line with NUL bytes among its entries (and SIZE 2 for a float)
// corrupted PCL's heap inside readHeader (an ASan CHECK in fuzz_pcd): the
// header is now refused before PCL parses it.
TEST(FuzzRegressions, PcdHeaderWithNulBytesInItsTypeLine) {
  const fs::path file = kCorpus / "fuzz_pcd/crash-nul-in-type-line.pcd";
  const std::string msg = input_error(file, [](const fs::path& f) { read_cloud_file(f); });
  EXPECT_NE(msg.find("crash-nul-in-type-line.pcd is not a readable pcd point cloud: line "),
            std::string::npos)
      << msg;
}

// COUNT "1-16..." read as 1 and 2^64 - 16: PCL's readHeader allocated 12 GB.
TEST(FuzzRegressions, PcdHeaderWithANegativeCount) {
  const fs::path file = kCorpus / "fuzz_pcd/oom-negative-count.pcd";
  const std::string msg = input_error(file, [](const fs::path& f) { read_cloud_file(f); });
  EXPECT_NE(msg.find("oom-negative-count.pcd is not a readable pcd point cloud: line 6: COUNT entries must be whole numbers"),
            std::string::npos)
      << msg;
}

// "DATAUNT" is a DATA line to PCL (it matches keys by their first letters),
// and SIZE 0 with no TYPE then overflowed a buffer in fromPCLPointCloud2.
TEST(FuzzRegressions, PcdHeaderWhoseDataKeyHasATail) {
  const fs::path file = kCorpus / "fuzz_pcd/crash-data-key-prefix.pcd";
  const std::string msg = input_error(file, [](const fs::path& f) { read_cloud_file(f); });
  EXPECT_NE(msg.find("crash-data-key-prefix.pcd is not a readable pcd point cloud: line "), std::string::npos) << msg;
}

// OpenCV's DICOM decoder (GDCM) aborted the process on this file: 128 bytes,
// then "DICM" and two more.
TEST(FuzzRegressions, DamagedDicomThatAborted) {
  const fs::path file = kCorpus / "fuzz_png/crash-damaged-dicom.png";
  const std::string msg = input_error(file, [](const fs::path& f) { read_image_file(f, cv::IMREAD_COLOR); });
  EXPECT_NE(msg.find("the image " + file.string() + " cannot be read: a DICOM file"), std::string::npos) << msg;
}

// A whole PNG declaring 524,295 x 327,680 pixels: cv::imdecode threw
// cv::Exception past read_image_file (std::terminate in a stage).
TEST(FuzzRegressions, PngTooLargeForOpenCvThatThrew) {
  const fs::path file = kCorpus / "fuzz_png/crash-oversized-header.png";
  for (int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_COLOR}) {
    const std::string msg = input_error(file, [&](const fs::path& f) { read_image_file(f, flags); });
    EXPECT_NE(msg.find("the image " + file.string() + " cannot be read: not a whole PNG: its header declares 524295 x "
                       "327680 pixels, more than OpenCV decodes"),
              std::string::npos)
        << msg;
  }
}

// Five bytes, "RIFF" and one more: the check for WebP's signature read past
// the end (std::out_of_range past read_image_file).
TEST(FuzzRegressions, ShortRiffThatThrewOutOfRange) {
  const fs::path file = kCorpus / "fuzz_png/crash-short-riff.png";
  const std::string msg = input_error(file, [](const fs::path& f) { read_image_file(f, cv::IMREAD_COLOR); });
  EXPECT_NE(msg.find("the image " + file.string() + " cannot be read: in no image format touchcloud reads"),
            std::string::npos)
      << msg;
}

// A PNG with an EXIF chunk (left to OpenCV, which may turn the image) whose
// header declares 393,216 x 2,048 pixels in 95 bytes of data: OpenCV
// allocated 2.4 GB before finding the data short. Its size is now checked
// first.
TEST(FuzzRegressions, PngWithExifAndAHugeHeaderThatAllocated) {
  const fs::path file = kCorpus / "fuzz_png/oom-exif-huge-header.png";
  const std::string msg = input_error(file, [](const fs::path& f) { read_image_file(f, cv::IMREAD_COLOR); });
  EXPECT_NE(msg.find("cannot be read: not a whole PNG: its image data (95 bytes) cannot hold the 393216 x 2048 pixels"),
            std::string::npos)
      << msg;
}
