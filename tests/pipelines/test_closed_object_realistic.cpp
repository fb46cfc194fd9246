// pipelines/closed_object_all_sides_realistic.yaml as shipped, on the 30 mm
// sphere's scene_realistic.yaml: every touch read from rendered images
// (dots detected, matched and triangulated with the calibrated, not the
// true, sensor) from above and from the sides. The touch points must lie
// on the sphere in the base frame whatever the palm's tilt: a pose applied
// only as a vertical press would put a 45 degree touch's points many mm off.
// The realistic gel's elastic spread (sigma 3 mm) holds it off a surface
// this curved, so the points lie outside the sphere by up to about 2.4 mm
// (measured with 10 and 60 touches: median 0.17-0.18 mm, 95th percentile
// 1.9-2.0 mm; a sphere fitted to them has a radius of 15.9-16.0 mm), where
// the ideal sensor's lie within 0.03 mm.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "cloud_files.hpp"
#include "test_support.hpp"

using touchcloud::test::run_cli;

TEST(ClosedObjectRealistic, TouchesFromEverySideReadFromImagesLieOnTheSphere) {
  touchcloud::test::TempDir dir;
  const auto source = touchcloud::test::source_dir();
  const auto r = run_cli({"run", (source / "pipelines/closed_object_all_sides_realistic.yaml").string(), "--scene",
                          (source / "sample_clouds/closed_objects/sphere/scene_realistic.yaml").string(), "--seed",
                          "1", "--quiet", "--set", "explore.max_iterations=8", "--out", (dir / "out").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = nlohmann::json::parse(touchcloud::test::read_file(dir / "out/summary.json"));
  EXPECT_EQ(s["metrics"]["sensor.touches"]["value"].get<double>(), 8);

  const touchcloud::PointCloud points = touchcloud::test::load_cloud(dir / "out/sphere_touch_points.pcd");
  ASSERT_GT(points.size(), 200u);
  const Eigen::Vector3d centre(0, 0, 15);  // the scene's sphere: radius 15 mm, resting on the table
  std::vector<double> outside;
  double lowest = 1e9, west = 0, east = 0;
  for (const auto& p : points) {
    const Eigen::Vector3d x(p.x, p.y, p.z);
    outside.push_back((x - centre).norm() - 15);
    lowest = std::min(lowest, x.z());
    west = std::min(west, x.x());
    east = std::max(east, x.x());
  }
  std::sort(outside.begin(), outside.end());
  EXPECT_GT(outside.front(), -0.3);  // never inside the sphere beyond the sensor's scatter
  EXPECT_LT(outside.back(), 3.0);    // nor farther out than the gel's spread holds it
  EXPECT_LT(outside[outside.size() / 2], 0.5);
  // Touched from the sides, not only from above: points below the equator
  // and on both sides of the sphere.
  EXPECT_LT(lowest, 15.0);
  EXPECT_LT(west, -10.0);
  EXPECT_GT(east, 10.0);
}
