// Optics, scoring and cloud files from the sensing library alone: this
// program is compiled with sensing's include paths only (the runtime's
// headers are not on them) and linked with libtouchcloud_sensing only;
// no_runtime.sh then reads what it and the library need at load. Every
// public sensing header is compiled into it too (sensing_headers.cpp, listed
// by CMake), so a header that includes the pipeline runtime breaks the build.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include <unistd.h>

#include "touchcloud/io/cloud_file.hpp"
#include "touchcloud/optics/snell.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"

namespace {

int failures = 0;

void expect_near(const char* what, double value, double expected, double tolerance) {
  if (std::abs(value - expected) <= tolerance) return;
  std::fprintf(stderr, "%s: %.17g, expected %.17g\n", what, value, expected);
  ++failures;
}

}  // namespace

int main() {
  using namespace touchcloud;
  // Snell: 30 degrees from air into an index of 1.5 leaves at asin(0.5 / 1.5).
  const double in = std::numbers::pi / 6;
  const optics::Refraction r = optics::refract({std::sin(in), 0, std::cos(in)}, {0, 0, 1}, 1.0, 1.5);
  expect_near("refracted sine", r.direction.x(), 0.5 / 1.5, 1e-15);

  // A cloud file written and read back.
  PointCloud cloud;
  for (int i = 0; i < 4; ++i) cloud.push_back(pcl::PointXYZ(float(i), float(2 * i), 1.0f));
  const auto file = std::filesystem::temp_directory_path() /
                    ("touchcloud_sensing_without_runtime_" + std::to_string(::getpid()) + ".ply");
  write_cloud_file(file, cloud, true);
  const CloudFile read = read_cloud_file(file);
  std::filesystem::remove(file);
  expect_near("points read back", double(read.cloud->size()), 4, 0);

  // Scoring: the points raised 0.5 mm are 0.5 mm from the ones read, either way.
  scoring::Points estimate = scoring::to_points(*read.cloud);
  for (auto& p : estimate) p.z() += 0.5;
  const scoring::NearestPointIndex truth(scoring::to_points(*read.cloud));
  const scoring::CloudScore score = scoring::score_estimate(estimate, truth);
  expect_near("chamfer", score.chamfer_symmetric_mm, 0.5, 1e-6);
  if (failures == 0) std::puts("sensing without the runtime: optics, cloud files and scoring as expected");
  return failures == 0 ? 0 : 1;
}
