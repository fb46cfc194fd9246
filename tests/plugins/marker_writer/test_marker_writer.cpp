// marker_writer: what it writes (CSV and JSON) reads back exactly, for stereo
// and one-camera sets; a failed write names the file; a run that fails
// leaves no marker file; a loop needs one file per iteration.
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline_fixture.hpp"
#include "stage_harness.hpp"
#include "touchcloud/types/marker_set.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;

namespace {

// Two left markers, one right, one pair; centres with no short decimal form.
MarkerSetPtr stereo_set() {
  auto set = std::make_shared<MarkerSet>();
  set->left = {{{412.25, 88.5}, 4, 0.93}, {{1.0 / 3.0, 200.0 / 7.0}, -1, 0.1 + 0.2}};
  set->right = {{{398.125, 88.75}, 4, 0.875}};
  set->matches = {{0, 0, 4}};
  set->timestamp_s = 1.5;
  return set;
}

MarkerSetPtr mono_set() {
  auto set = std::make_shared<MarkerSet>();
  set->views = {CameraView::Mono};
  set->mono = {{{17.5, 23.25}, -1, 0.5}};
  return set;
}

struct Row {
  int id;
  std::string view;
  double x, y, quality;
};

std::vector<Row> read_csv(const std::filesystem::path& file, std::string& header) {
  std::ifstream in(file);
  std::getline(in, header);
  std::vector<Row> rows;
  for (std::string line; std::getline(in, line);) {
    std::stringstream cells(line);
    std::string id, view, x, y, q;
    std::getline(cells, id, ','), std::getline(cells, view, ','), std::getline(cells, x, ',');
    std::getline(cells, y, ','), std::getline(cells, q, ',');
    rows.push_back({std::stoi(id), view, std::stod(x), std::stod(y), std::stod(q)});
  }
  return rows;
}

// Writes `set` with a harness whose staging folder is `dir`; the file written.
std::filesystem::path write_set(const test::TempDir& dir, const std::string& path, const MarkerSetPtr& set) {
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  test::StageHarness stage("marker_writer", {{"path", path}}, "write", settings);
  stage.configure();
  stage.process({{"markers", std::any(set)}}, {});
  EXPECT_EQ(stage.metric("markers_written"), set->left.size() + set->right.size() + set->mono.size());
  return dir / path;
}

cv::Mat dots_image(int dots) {
  cv::Mat image(80, 120, CV_8UC1, cv::Scalar(200));
  for (int i = 0; i < dots; ++i) cv::circle(image, {20 + 25 * i, 40}, 4, cv::Scalar(40), cv::FILLED);
  return image;
}

}  // namespace

TEST(MarkerWriter, CsvHoldsEveryMarkerOfEachViewExactly) {
  test::TempDir dir;
  std::string header;
  const auto rows = read_csv(write_set(dir, "markers.csv", stereo_set()), header);
  EXPECT_EQ(header, "id,view,x_px,y_px,quality");
  ASSERT_EQ(rows.size(), 3u);
  const MarkerSetPtr set = stereo_set();
  const std::vector<std::pair<const Marker*, std::string>> expected{
      {&set->left[0], "left"}, {&set->left[1], "left"}, {&set->right[0], "right"}};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].id, expected[i].first->id);
    EXPECT_EQ(rows[i].view, expected[i].second);
    EXPECT_EQ(rows[i].x, expected[i].first->centre_px.x());  // shortest exact form: bit for bit
    EXPECT_EQ(rows[i].y, expected[i].first->centre_px.y());
    EXPECT_EQ(rows[i].quality, expected[i].first->quality);
  }
  EXPECT_EQ(test::read_file(dir / "markers.csv").substr(header.size() + 1, 24), "4,left,412.25,88.5,0.93\n");
}

TEST(MarkerWriter, JsonHoldsMarkersViewsMatchesAndTime) {
  test::TempDir dir;
  const auto j = nlohmann::json::parse(test::read_file(write_set(dir, "markers.json", stereo_set())));
  EXPECT_EQ(j.at("timestamp_s"), 1.5);
  EXPECT_EQ(j.at("views"), nlohmann::json::array({"left", "right"}));
  ASSERT_EQ(j.at("markers").size(), 3u);
  const auto& second = j.at("markers")[1];
  EXPECT_EQ(second.at("id"), -1);
  EXPECT_EQ(second.at("view"), "left");
  EXPECT_EQ(second.at("x_px").get<double>(), 1.0 / 3.0);
  EXPECT_EQ(second.at("y_px").get<double>(), 200.0 / 7.0);
  EXPECT_EQ(second.at("quality").get<double>(), 0.1 + 0.2);
  EXPECT_EQ(j.at("markers")[2].at("view"), "right");
  EXPECT_EQ(j.at("matches"), nlohmann::json::parse(R"([{"id": 4, "left": 0, "right": 0}])"));
}

TEST(MarkerWriter, OneCamerasMarkersCarryItsView) {
  test::TempDir dir;
  std::string header;
  const auto rows = read_csv(write_set(dir, "mono.csv", mono_set()), header);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].view, "mono");
  EXPECT_EQ(rows[0].x, 17.5);
  const auto j = nlohmann::json::parse(test::read_file(write_set(dir, "mono.json", mono_set())));
  EXPECT_EQ(j.at("views"), nlohmann::json::array({"mono"}));
  EXPECT_TRUE(j.at("matches").empty());
}

TEST(MarkerWriter, AFailedWriteNamesTheFile) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "markers.csv");  // a folder where the file should go
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  test::StageHarness stage("marker_writer", {{"path", std::string("markers.csv")}}, "write", settings);
  stage.configure();
  try {
    stage.process({{"markers", std::any(stereo_set())}}, {});
    FAIL() << "wrote into a folder";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "markers.csv").string()), std::string::npos) << e.what();
  }
}

class MarkerWriterPipeline : public touchcloud::test::PipelineFixture {
 protected:
  // Reads gel_<k>.png in a loop, detects its markers and writes them to `path`.
  std::string pipeline(const std::string& path, int iterations, const std::string& extra = "") {
    return "stages:\n"
           "  - id: frames\n"
           "    loop:\n"
           "      max_iterations: " + std::to_string(iterations) + "\n"
           "      stages:\n"
           "        - id: read\n"
           "          plugin: image_reader\n"
           "          params: {path: 'gel_{iteration}.png'}\n"
           "        - id: detect\n"
           "          plugin: marker_detection\n"
           "          inputs: {image: read.image}\n"
           "        - id: write\n"
           "          plugin: marker_writer\n"
           "          params: {path: '" + path + "'}\n"
           "          inputs: {markers: detect.markers}\n" + extra;
  }
  void write_images() {
    for (int k = 0; k < 3; ++k) cv::imwrite((dir_ / ("gel_" + std::to_string(k) + ".png")).string(), dots_image(k + 1));
  }
  RunResult run(const std::string& yaml) {
    write_images();
    Pipeline p = load(yaml);
    RunOptions o;
    o.quiet = true;
    o.out_dir = dir_ / "out";
    return run_pipeline(p, o);
  }
};

TEST_F(MarkerWriterPipeline, OneFilePerIterationReadsBack) {
  const RunResult r = run(pipeline("markers_{iteration}.csv", 3));
  EXPECT_EQ(r.record.outputs, (std::vector<std::string>{"markers_0.csv", "markers_1.csv", "markers_2.csv"}));
  for (int k = 0; k < 3; ++k) {
    std::string header;
    const auto rows = read_csv(dir_ / "out" / ("markers_" + std::to_string(k) + ".csv"), header);
    ASSERT_EQ(rows.size(), static_cast<std::size_t>(k + 1));
    for (int i = 0; i <= k; ++i) {
      EXPECT_EQ(rows[i].view, "mono");
      EXPECT_NEAR(rows[i].x, 20 + 25 * i, 0.05);
      EXPECT_NEAR(rows[i].y, 40, 0.05);
      EXPECT_GT(rows[i].quality, 0.5);
    }
  }
}

TEST_F(MarkerWriterPipeline, ALoopWritingOneFileOverAndOverIsRefused) {
  try {
    run(pipeline("markers.csv", 2));
    FAIL() << "wrote markers.csv twice";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("put '{iteration}' in it"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "markers.csv"));
}

TEST_F(MarkerWriterPipeline, ARunThatFailsLaterLeavesNoMarkerFile) {
  // The first iteration writes markers_0.csv; the second fails.
  const std::string failing = "        - id: fail\n          plugin: test_throwing\n          params: {fail_at: 1}\n";
  EXPECT_ANY_THROW(run(pipeline("markers_{iteration}.csv", 2, failing)));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "markers_0.csv"));
}

TEST_F(MarkerWriterPipeline, AnUnknownFormatIsRefusedAtValidation) {
  write_images();  // the reader checks its sequence at validation too
  const auto d = errors(pipeline("markers.txt", 1));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "unsupported extension '.txt' (use .csv or .json)")) << d[0].str();
}
