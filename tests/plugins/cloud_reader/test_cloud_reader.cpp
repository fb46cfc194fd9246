// cloud_reader: good files load; empty, corrupt and non-finite ones are
// refused at validation with the parameter's position.
#include "cloud_files.hpp"
#include "pipeline_fixture.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

class CloudReader : public touchcloud::test::PipelineFixture {
 protected:
  std::string pipeline(const std::string& file, const std::string& extra = "") {
    return "stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: " + file + extra + "}\n";
  }
  Diagnostic single_error(const std::string& file, const std::string& extra = "") {
    const auto d = errors(pipeline(file, extra));
    EXPECT_EQ(d.size(), 1u);
    return d.empty() ? Diagnostic{} : d[0];
  }
};

TEST_F(CloudReader, ReadsPcdAndReportsThePointCount) {
  touchcloud::test::save_pcd(dir_ / "grid.pcd", touchcloud::test::grid_cloud(4, 1.0));
  Pipeline p = load(pipeline("grid.pcd"));
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(r.record.metrics.at("read.points").values.at(0), 16);
}

TEST_F(CloudReader, EmptyPcdIsRefused) {
  touchcloud::test::write_file(dir_ / "empty.pcd",
                               "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                               "WIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\nDATA ascii\n");
  const Diagnostic d = single_error("empty.pcd");
  EXPECT_TRUE(mentions(d, "contains no points")) << d.str();
  EXPECT_EQ(d.where.line, 4);
}

TEST_F(CloudReader, ZeroByteAndCorruptFilesAreRefused) {
  touchcloud::test::write_file(dir_ / "zero.pcd", "");
  EXPECT_TRUE(mentions(single_error("zero.pcd"), "is empty (0 bytes)"));
  // PCL 1.13 itself crashes on a PCD without a header; the reader must not.
  touchcloud::test::write_file(dir_ / "garbage.pcd", "this is not a point cloud\n\x01\x02\x03");
  EXPECT_TRUE(mentions(single_error("garbage.pcd"), "no valid PCD header"));
  touchcloud::test::write_file(dir_ / "noxyz.pcd",
                               "VERSION 0.7\nFIELDS a b c\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                               "WIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2 3\n");
  EXPECT_TRUE(mentions(single_error("noxyz.pcd"), "has no 'x' field"));
  // A header promising more points than the file holds.
  touchcloud::test::write_file(dir_ / "truncated.pcd",
                               "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                               "WIDTH 5\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 5\nDATA binary\n\x01\x02");
  EXPECT_TRUE(mentions(single_error("truncated.pcd"), "is not a readable pcd point cloud"));
  touchcloud::test::write_file(dir_ / "garbage.ply", "ply\nformat nonsense\n");
  EXPECT_TRUE(mentions(single_error("garbage.ply"), "is not a readable ply point cloud"));
  touchcloud::test::write_file(dir_ / "empty.ply",
                               "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\n");
  const Diagnostic d = single_error("empty.ply");
  EXPECT_TRUE(mentions(d, "contains no points") || mentions(d, "is not a readable ply")) << d.str();
}

TEST_F(CloudReader, UnsupportedExtensionIsRefused) {
  touchcloud::test::write_file(dir_ / "cloud.xyz", "1 2 3\n");
  EXPECT_TRUE(mentions(single_error("cloud.xyz"), "unsupported extension '.xyz'"));
}

TEST_F(CloudReader, NonFinitePointsAreRefusedOrDroppedAndCounted) {
  touchcloud::test::write_file(dir_ / "nan.pcd",
                               "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                               "WIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n"
                               "0 0 0\nnan 1 1\n2 2 2\n");
  EXPECT_TRUE(mentions(single_error("nan.pcd"), "1 points with non-finite coordinates"));
  Pipeline p = load(pipeline("nan.pcd", ", on_nonfinite: drop"));
  RunOptions o;
  o.quiet = true;
  const RunResult r = run_pipeline(p, o);
  EXPECT_EQ(r.record.metrics.at("read.points").values.at(0), 2);
  EXPECT_EQ(r.record.metrics.at("read.nonfinite_dropped").values.at(0), 1);
}
