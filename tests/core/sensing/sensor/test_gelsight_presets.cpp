// The shipped GelSight-type sensor presets (sample_clouds/sensors/) read as
// sensors with the figures their comments state.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/sensor/gelsight_sensor.hpp"

using namespace touchcloud;

TEST(GelSightPresets, TheMiniAndTheDigitReadWithTheirPublishedImageSizeAndFrameRate) {
  const auto mini = sensor::load_gelsight_sensor(test::source_dir() / "sample_clouds/sensors/gelsight_mini.yaml");
  EXPECT_EQ(mini.name, "gelsight_mini");
  EXPECT_EQ(mini.width_px, 320);
  EXPECT_EQ(mini.height_px, 240);
  EXPECT_EQ(mini.fps, 25);
  EXPECT_NEAR(mini.pad_width_mm(), 18.6, 0.3);  // the data sheet's sensing area
  EXPECT_NEAR(mini.pad_height_mm(), 14.3, 0.3);
  const auto digit = sensor::load_gelsight_sensor(test::source_dir() / "sample_clouds/sensors/digit.yaml");
  EXPECT_EQ(digit.name, "digit");
  EXPECT_EQ(digit.width_px, 320);
  EXPECT_EQ(digit.height_px, 240);
  EXPECT_EQ(digit.fps, 60);
  EXPECT_GT(digit.gel_thickness_mm, 0);
}
