// pipelines/detect_markers_mono.yaml as shipped: the sample single-camera
// images' markers, written as CSV and read back, against the truth beside
// each image: recall and precision at least 0.97, every row of view mono.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "realistic_markers.hpp"
#include "test_support.hpp"
#include "touchcloud/pipeline.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  std::getline(in, line);  // header
  for (; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace

TEST(MarkerImagesPipeline, FindsTheSampleImagesMarkers) {
  test::TempDir dir;
  const fs::path samples = test::source_dir() / "sample_clouds/gelsight_markers";
  PluginRegistry registry;
  Pipeline p = Pipeline::load(test::source_dir() / "pipelines/detect_markers_mono.yaml", {}, registry);
  RunOptions o;
  o.quiet = true;
  o.out_dir = dir / "out";
  run_pipeline(p, o);
  test::RealisticScore total;
  for (int k = 0; k < 3; ++k) {
    const std::string name = "markers_" + std::to_string(k);
    test::RealisticImage truth;
    for (const auto& r : read_csv(samples / (name + "_truth.csv"))) {
      ASSERT_EQ(r.size(), 7u);
      truth.dots.push_back({{std::stod(r[0]), std::stod(r[1])}, std::stod(r[2]), std::stod(r[3]), std::stod(r[4]),
                            r[5] == "1", r[6] == "1"});
    }
    std::vector<Eigen::Vector2d> found;
    for (const auto& r : read_csv(dir / "out" / (name + ".csv"))) {
      ASSERT_EQ(r.size(), 5u);
      EXPECT_EQ(r[1], "mono");
      EXPECT_GE(std::stod(r[4]), 0.1);  // min_quality
      found.emplace_back(std::stod(r[2]), std::stod(r[3]));
    }
    total += test::score_realistic(found, truth);
  }
  std::cout << "[ score    ] " << total.str() << "\n";
  EXPECT_GT(total.whole_dots, 200);
  EXPECT_GE(total.recall(), 0.97) << total.str();
  EXPECT_GE(total.precision(), 0.97) << total.str();
  EXPECT_EQ(total.extra_on_a_dot, 0) << total.str();
}
