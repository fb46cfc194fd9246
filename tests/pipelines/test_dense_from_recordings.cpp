// pipelines/dense_from_recordings.yaml as shipped: raw, distorted,
// unrectified colour pairs (sample_clouds/colour_recording) rectified from
// the sensor file and turned into the contact cloud, against the press's
// true contact cloud; and a sensor file of other cameras refused.
#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

const fs::path kPipeline = test::source_dir() / "pipelines/dense_from_recordings.yaml";

double chamfer_of(const std::string& out_err) {
  const auto at = out_err.find("score.chamfer_est_to_gt");
  if (at == std::string::npos) return -1;
  return std::stod(out_err.substr(out_err.find_first_of("0123456789", at + 23)));
}

}  // namespace

TEST(DenseFromRecordings, RawPairsGiveTheTrueContactThroughThePlate) {
  test::TempDir dir;
  const auto refracted = test::run_cli({"run", kPipeline.string(), "--out", (dir / "a").string()});
  ASSERT_EQ(refracted.exit_code, 0) << refracted.err;
  EXPECT_TRUE(fs::exists(dir / "a" / "contact_sensor_0.pcd"));
  // Within a sixth of a millimetre of the truth (SGBM on rectified-again pairs, 640 x 360).
  const double through_plate = chamfer_of(refracted.out + refracted.err);
  EXPECT_GT(through_plate, 0);
  EXPECT_LT(through_plate, 0.17) << "mm";
  // The paper's straight rays on the same disparities miss by millimetres.
  const auto straight = test::run_cli({"run", kPipeline.string(), "--out", (dir / "b").string(), "--set",
                                       "cloud.refraction=false"});
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  EXPECT_GT(chamfer_of(straight.out + straight.err), 5.0) << "mm";
}

TEST(DenseFromRecordings, ASensorFileOfOtherCamerasIsBadInputAndNothingIsWritten) {
  test::TempDir dir;
  const auto r = test::run_cli({"run", kPipeline.string(), "--out", (dir / "out").string(), "--set",
                                "rectify.sensor=" + (test::source_dir() / "sample_clouds/fox_mask/scene_dense.yaml").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the left image is 640 x 360 px; the sensor file's cameras are 1280 x 720 px"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}
