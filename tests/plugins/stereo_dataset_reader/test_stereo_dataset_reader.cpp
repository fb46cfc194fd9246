// stereo_dataset_reader: pairs without ground truth, and the index line of a
// missing or unreadable file or a malformed index.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "dataset_fixture.hpp"
#include "touchcloud/io/stereo_dataset.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
using namespace touchcloud::test::dataset;

TEST(StereoDataset, ReadsPairsWithoutTruthAndRefusesTruthThatIsNotThere) {
  TempDir dir;
  write_dataset(dir.path(), false);
  StageHarness r("stereo_dataset_reader", {{"index", index_of(dir)}});
  r.configure();
  EXPECT_TRUE(same(r.process_one<ColourStereoFramePtr>({}, "frame")->right, frame(1)->right));
  try {
    r.process({}, {"truth"});
    FAIL() << "truth of a row without any";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("index.csv:3: output 'truth' is read, but this row lists no ground truth"),
              std::string::npos)
        << e.what();
  }
}

TEST(StereoDataset, NamesTheIndexLineOfAMissingOrUnreadableFile) {
  TempDir dir;
  write_dataset(dir.path(), true);
  std::filesystem::remove(dir / "data" / "truth" / "000001_contact_mask.png");
  try {
    StageHarness r("stereo_dataset_reader", {{"index", index_of(dir)}});
    r.configure();
    FAIL() << "a missing file";
  } catch (const ParameterError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("index.csv:3: contact_mask file 'truth/000001_contact_mask.png' is missing"), std::string::npos)
        << m;
  }
  TempDir dir2;
  write_dataset(dir2.path(), true);
  write_file(dir2 / "data" / "pairs" / "000000_left.png", "not a png");
  StageHarness r("stereo_dataset_reader", {{"index", index_of(dir2)}});
  r.configure();
  try {
    r.process({}, {"frame"});
    FAIL() << "an unreadable file";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("index.csv:2: left file 'pairs/000000_left.png' cannot be read"), std::string::npos) << m;
  }
}

TEST(StereoDataset, RefusesAMalformedIndex) {
  TempDir dir;
  write_dataset(dir.path(), false);
  write_file(dir / "data" / "index.csv", "index,timestamp_s,left,right\n0,0,a.png,b.png\n");
  try {
    io::read_dataset_index(dir / "data");
    FAIL() << "a malformed index";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("index.csv:1: the first line must name the columns"), std::string::npos)
        << e.what();
  }
}


TEST(StereoDataset, ReadsAnIndexWithWindowsLineEnds) {
  TempDir dir;
  write_dataset(dir.path(), true);
  const auto lf = io::read_dataset_index(dir / "data");
  std::string text = read_file(dir / "data" / "index.csv"), crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write_file(dir / "data" / "index.csv", crlf);
  const auto rows = io::read_dataset_index(dir / "data");
  ASSERT_EQ(rows.size(), lf.size());
  EXPECT_EQ(rows.back().files, lf.back().files);  // no '\r' left on the last column
}

// As a spreadsheet saves UTF-8 CSV: a byte order mark before the header.
TEST(StereoDataset, ReadsAnIndexWithAByteOrderMark) {
  TempDir dir;
  write_dataset(dir.path(), true);
  const auto plain = io::read_dataset_index(dir / "data");
  write_file(dir / "data" / "index.csv", "\xEF\xBB\xBF" + read_file(dir / "data" / "index.csv"));
  const auto rows = io::read_dataset_index(dir / "data");
  ASSERT_EQ(rows.size(), plain.size());
  EXPECT_EQ(rows.front().files, plain.front().files);
}

// OpenCV decodes a JPEG cut short with its missing part grey: refused,
// naming the index line and the file.
TEST(StereoDataset, AJpegCutShortIsRefusedNamingTheFile) {
  TempDir dir;
  write_dataset(dir.path(), false);
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", frame(1)->left, jpeg));
  write_file(dir / "data" / "pairs" / "000000_left.png", std::string(jpeg.begin(), jpeg.begin() + jpeg.size() / 2));
  StageHarness r("stereo_dataset_reader", {{"index", index_of(dir)}});
  r.configure();
  try {
    r.process({}, {"frame"});
    FAIL() << "a JPEG cut short";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("index.csv:2: left file 'pairs/000000_left.png' cannot be read: not a whole JPEG"),
              std::string::npos)
        << e.what();
  }
}
