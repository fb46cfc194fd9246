// map_writer: a height map read back from its 16-bit PNG or TIFF is the
// map to within half a count (invalid pixels and heights below zero 0), the
// PNG carries its scale, summary.json's attributes say it for both, and a
// height the 16 bits cannot hold stops the run naming the scale that would.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "stage_harness.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/imaging/height_map_file.hpp"
#include "touchcloud/types/height_map.hpp"

using namespace touchcloud;

namespace {

HeightMapPtr dome(double peak_mm) {
  auto h = std::make_shared<HeightMap>();
  h->height_mm = cv::Mat(30, 40, CV_32FC1);
  for (int v = 0; v < 30; ++v)
    for (int u = 0; u < 40; ++u) {
      const double r2 = ((u - 20.0) * (u - 20.0) + (v - 15.0) * (v - 15.0)) / 100.0;
      h->height_mm.at<float>(v, u) = static_cast<float>(peak_mm * (1 - r2));  // negative beyond r = 10 px
    }
  h->valid = cv::Mat(30, 40, CV_8UC1, cv::Scalar(255));
  h->valid.at<std::uint8_t>(15, 21) = 0;
  h->contact_mask = h->height_mm > 0.05;
  h->mm_per_px = 0.06;
  h->sensor = "gelsight_mini";
  return h;
}

}  // namespace

TEST(MapWriter, AHeightMapReadsBackFromItsSixteenBitFileWithItsScale) {
  for (const std::string name : {"height.png", "height.tiff"}) {
    test::TempDir dir;
    RunSettings settings;
    settings.staging_dir = dir.path();
    settings.quiet = true;
    test::StageHarness writer("map_writer",
                              {{"path", name}, {"mm_per_count", 0.001}, {"mask_path", std::string("contact.png")}},
                              "write", settings);
    writer.configure();
    const HeightMapPtr map = dome(1.5);
    writer.process({{"height", map}}, {});
    const cv::Mat counts = cv::imread((dir / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(counts.type(), CV_16UC1) << name;
    long below = 0;
    for (int v = 0; v < 30; ++v)
      for (int u = 0; u < 40; ++u) {
        const double h = map->height_mm.at<float>(v, u), read = counts.at<std::uint16_t>(v, u) * 0.001;
        if (u == 21 && v == 15) {
          EXPECT_EQ(read, 0);  // invalid
        } else if (h < 0) {
          EXPECT_EQ(read, 0);
          ++below;
        } else {
          EXPECT_NEAR(read, h, 0.0005 + 1e-9) << name << " at " << u << ", " << v;
        }
      }
    if (name == "height.png") EXPECT_EQ(imaging::read_height_scale(dir / name), 0.001);
    const auto& a = writer.record().artifacts;
    ASSERT_EQ(a.size(), 2u);
    EXPECT_EQ(a[0].role, ArtifactRole::map);
    EXPECT_EQ(std::get<double>(a[0].attributes.at("mm_per_count")), 0.001);
    EXPECT_EQ(std::get<std::string>(a[0].attributes.at("unit")), "mm");
    EXPECT_EQ(std::get<std::int64_t>(a[0].attributes.at("below_zero_px")), below);
    EXPECT_EQ(std::get<std::int64_t>(a[0].attributes.at("invalid_px")), 1);
    const cv::Mat mask = cv::imread((dir / "contact.png").string(), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(cv::countNonZero(mask != map->contact_mask), 0);
  }
}

TEST(MapWriter, AHeightBeyondSixteenBitsStopsTheRunNamingTheScaleThatWouldHoldIt) {
  test::TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  test::StageHarness writer("map_writer", {{"path", std::string("h.png")}}, "write", settings);
  writer.configure();
  const std::string e = test::input_error_of([&] { writer.process({{"height", dome(7.0)}}, {}); });
  EXPECT_NE(e.find("a height of 7 mm at pixel (20, 15) does not fit 16 bits at 0.0001 mm per count"), std::string::npos)
      << e;
  EXPECT_NE(e.find("raise mm_per_count to at least 0.0001068"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir / "h.png"));
}
