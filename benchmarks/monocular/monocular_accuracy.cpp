// The classical depth of a GelSight-type sensor on held-out simulated presses
// of objects the calibration never saw: a sphere, a cylinder's edge, a
// screw-like thread, text relief and the fox mask's nose. Per object: height
// RMSE and largest error (mm) over the true contact region, contact IoU and
// F1, for photometric_depth with a zero and with a free border, from the
// shipped calibration (sample_clouds/gelsight_ball/photometric_calibration.yaml).
// With the learning library, the same presses through ContactNet and TactileDepthNet
// (ContactNet and TactileDepthNet, the shipped checkpoints under models/,
// trained on other objects: pipelines/tactile_nets_*.yaml). Time per frame:
// bench_photometric_depth (one core), bench_tactile_nets (both, 1 and 2 threads).
//
//   build/benchmarks/bin/monocular_accuracy [--noise SIGMA_GREY] [--out benchmarks/monocular]
//       [--contact-net FILE] [--depth-net FILE] [--ranks N]
//
// With --ranks N the five presses spread over one `mpirun -n N` job (this
// program once per case, scripts/mpi_launch.py); the same table.
//
// writes results.md (and prints it).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>

#include <stdlib.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/file_write.hpp"
#include "touchcloud/imaging/photometric_depth_solver.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/simulation/gelsight_simulation.hpp"
#ifdef TOUCHCLOUD_WITH_NETWORKS
#include "touchcloud/learning/tactile_net_pair.hpp"
#endif

using namespace touchcloud;
using simulation::ObjectSurface;

namespace {

const std::string kSource = TOUCHCLOUD_SOURCE_DIR;

// An object given by its height over the table (mm), sampled for max_height_mm.
class HeightFunction final : public ObjectSurface {
 public:
  explicit HeightFunction(std::function<double(double, double)> f) : f_(std::move(f)) {}
  double height_mm(const Eigen::Vector2d& xy) const override { return std::max(0.0, f_(xy.x(), xy.y())); }
  double max_height_mm(const Eigen::Vector2d& c, double r) const override {
    double m = 0;
    for (double y = -r; y <= r; y += 0.05)
      for (double x = -r; x <= r; x += 0.05)
        if (x * x + y * y <= r * r) m = std::max(m, height_mm(c + Eigen::Vector2d(x, y)));
    return m;
  }

 private:
  std::function<double(double, double)> f_;
};

// "TC" raised 0.4 mm on a block 10 mm high, letters 8 mm tall.
std::shared_ptr<ObjectSurface> text_relief() {
  auto letters = std::make_shared<cv::Mat>(cv::Mat::zeros(400, 600, CV_8UC1));  // 0.05 mm per pixel, centred
  cv::putText(*letters, "TC", {90, 290}, cv::FONT_HERSHEY_SIMPLEX, 6.0, cv::Scalar(255), 30, cv::LINE_AA);
  cv::GaussianBlur(*letters, *letters, cv::Size(0, 0), 1.5);  // 0.075 mm rounding of the letters' walls
  return std::make_shared<HeightFunction>([letters](double x, double y) {
    const double u = x / 0.05 + 300, v = 200 - y / 0.05;
    if (u < 0 || v < 0 || u >= 599 || v >= 399) return 10.0;
    const int i = static_cast<int>(u), j = static_cast<int>(v);
    const double a = u - i, b = v - j;
    const auto at = [&](int jj, int ii) { return letters->at<std::uint8_t>(jj, ii) / 255.0; };
    const double s = (1 - b) * ((1 - a) * at(j, i) + a * at(j, i + 1)) + b * ((1 - a) * at(j + 1, i) + a * at(j + 1, i + 1));
    return 10.0 + 0.4 * s;
  });
}

struct Case {
  std::string name;
  std::shared_ptr<const ObjectSurface> object;
  Eigen::Vector2d target;
  double press_mm;
};

std::vector<Case> cases() {
  auto fox_scene = simulation::load_scene(kSource + "/sample_clouds/fox_mask/scene_gelsight.yaml");
  std::shared_ptr<const ObjectSurface> fox = simulation::make_object_surface(fox_scene.object);
  return {
      {"sphere (radius 5 mm)", std::make_shared<HeightFunction>([](double x, double y) {
         const double r2 = x * x + y * y;
         return r2 < 25 ? 5.0 + std::sqrt(25 - r2) : 0.0;
       }), {0.7, 0.4}, 0.5},
      {"cylinder edge (radius 6 mm, flat top)", std::make_shared<HeightFunction>([](double x, double y) {
         return std::hypot(x, y) < 6 ? 10.0 : 0.0;
       }), {6.0, 0.0}, 0.4},
      {"screw thread (1 mm pitch on a 4 mm radius)", std::make_shared<HeightFunction>([](double x, double y) {
         if (std::abs(y) >= 4) return 0.0;
         const double phase = (x + 0.1 * y) / 1.0;
         const double tri = 2 * std::abs(phase - std::floor(phase) - 0.5);  // 0 at the crest, 1 at the root
         return 6.0 + std::sqrt(16 - y * y) - 0.3 * tri;
       }), {0.0, 0.0}, 0.5},
      {"text relief ('TC', 0.4 mm)", text_relief(), {0.0, 0.0}, 0.3},
      {"fox mask nose", fox, {0.0, -46.0}, 0.5},
  };
}

struct Scores {
  double rmse = 0, max_error = 0, iou = 0, f1 = 0;
  long contact_px = 0;
};

Scores score(const cv::Mat& height_mm, const cv::Mat& contact_mask, const HeightMap& truth) {
  Scores s;
  double sum2 = 0;
  for (int v = 0; v < truth.height_mm.rows; ++v)
    for (int u = 0; u < truth.height_mm.cols; ++u) {
      if (!truth.contact_mask.at<std::uint8_t>(v, u)) continue;
      const double e = height_mm.at<float>(v, u) - truth.height_mm.at<float>(v, u);
      sum2 += e * e;
      s.max_error = std::max(s.max_error, std::abs(e));
      ++s.contact_px;
    }
  s.rmse = s.contact_px ? std::sqrt(sum2 / s.contact_px) : 0;
  const double tp = cv::countNonZero(contact_mask & truth.contact_mask);
  const double fp = cv::countNonZero(contact_mask & ~truth.contact_mask);
  const double fn = cv::countNonZero(~contact_mask & truth.contact_mask);
  s.iou = tp / std::max(1.0, tp + fp + fn);
  s.f1 = 2 * tp / std::max(1.0, 2 * tp + fp + fn);
  return s;
}

// What every case needs: the calibration, the networks, the scene.
struct Setup {
  sensor::PhotometricCalibration calibration;
#ifdef TOUCHCLOUD_WITH_NETWORKS
  std::unique_ptr<learning::TactileNetPair> nets;
#endif
  simulation::Scene scene;
};

// The table's rows of one case: the press simulated and scored by each method.
std::string case_rows(const Case& c, const Setup& setup) {
  std::ostringstream table;
  table << std::fixed << std::setprecision(3);
  simulation::GelSightSimulation sim(setup.scene, 1, c.object);
  for (int i = 0; i < 100000; ++i)
    if (sim.step(c.target, false).travel_past_contact_mm >= c.press_mm) break;
  const cv::Mat image = sim.render().image, reference = sim.render_reference().image;
  const HeightMap truth = sim.height_truth(0.05);
  auto row = [&](const std::string& method, const Scores& s) {
    table << "| " << c.name << " | " << c.press_mm << " | " << s.contact_px << " | " << method << " | " << s.rmse
          << " | " << s.max_error << " | " << s.iou << " | " << s.f1 << " |\n";
  };
  for (auto border : {imaging::PoissonBorder::Zero, imaging::PoissonBorder::Free}) {
    imaging::DepthOptions options;
    options.border = border;
    imaging::PhotometricDepthSolver solver(setup.calibration, options);
    const imaging::DepthResult r = solver.solve(image, reference);
    row(border == imaging::PoissonBorder::Zero ? "classical, zero border" : "classical, free border",
        score(r.height_mm, r.contact_mask, truth));
  }
#ifdef TOUCHCLOUD_WITH_NETWORKS
  const learning::TactilePrediction p = setup.nets->predict(image, reference);
  row("networks", score(p.height_mm, p.contact_probability > 0.5, truth));
#endif
  return table.str();
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Every case's rows from one `mpirun -n RANKS` job (scripts/mpi_launch.py):
// this program once per case, with --case I --rows FILE. Empty on failure.
std::optional<std::vector<std::string>> rows_over_ranks(const char* self, int ranks, std::size_t count,
                                                        const std::vector<std::string>& passed_on) {
  std::string folder_template = (std::filesystem::temp_directory_path() / "monocular-XXXXXX").string();
  if (!mkdtemp(folder_template.data())) {
    std::cerr << "monocular_accuracy: cannot make a folder in " << std::filesystem::temp_directory_path() << "\n";
    return std::nullopt;
  }
  const std::filesystem::path folder = folder_template;
  nlohmann::json commands = nlohmann::json::array();
  for (std::size_t i = 0; i < count; ++i) {
    std::vector<std::string> command = {std::filesystem::absolute(self).string(), "--case", std::to_string(i),
                                        "--rows", (folder / ("rows-" + std::to_string(i) + ".md")).string()};
    command.insert(command.end(), passed_on.begin(), passed_on.end());
    commands.push_back(command);
  }
  touchcloud::write_file(folder / "commands.json", commands.dump());
  const std::string launch = "python3 '" + kSource + "/scripts/mpi_launch.py' --ranks " + std::to_string(ranks) +
                             " '" + (folder / "commands.json").string() + "'";
  std::optional<std::vector<std::string>> rows;
  if (std::system(launch.c_str()) == 0) {
    rows.emplace();
    for (std::size_t i = 0; i < count; ++i)
      rows->push_back(read_text(folder / ("rows-" + std::to_string(i) + ".md")));
  }
  std::filesystem::remove_all(folder);
  return rows;
}

}  // namespace

static int run(int argc, char** argv) {
  const char* usage =
      "usage: monocular_accuracy [--noise SIGMA_GREY] [--out DIR] [--contact-net FILE] [--depth-net FILE] "
      "[--ranks N]\n";
  double noise = 0;
  int ranks = 1;
  long only_case = -1;
  std::string out, rows_file;
  std::string contact_net = kSource + "/models/contact_net_w8.ckpt", depth_net = kSource + "/models/tactile_depthnet_w8.ckpt";
  std::vector<std::string> passed_on;  // what every case's run needs again under --ranks
  for (int i = 1; i < argc; i += 2) {
    const std::string key = argv[i];
    if (i + 1 >= argc) {
      std::cerr << "monocular_accuracy: " << key << " needs a value\n" << usage;
      return 2;
    }
    const std::string value = argv[i + 1];
    if (key == "--noise") noise = std::stod(value);
    else if (key == "--out") out = value;
    else if (key == "--contact-net") contact_net = value;
    else if (key == "--depth-net") depth_net = value;
    else if (key == "--ranks") ranks = std::stoi(value);
    else if (key == "--case") only_case = std::stol(value);  // one case's rows into --rows (what --ranks runs)
    else if (key == "--rows") rows_file = value;
    else {
      std::cerr << usage;
      return 2;
    }
    if (key == "--noise" || key == "--contact-net" || key == "--depth-net") passed_on.insert(passed_on.end(), {key, value});
  }
  const std::vector<Case> all = cases();
  if (ranks < 1 || only_case >= static_cast<long>(all.size()) || (only_case >= 0) != !rows_file.empty()) {
    std::cerr << "monocular_accuracy: --ranks must be >= 1, and --case (0-" << all.size() - 1
              << ") comes with --rows\n" << usage;
    return 2;
  }
  std::vector<std::string> rows;
  if (ranks > 1) {
    auto spread = rows_over_ranks(argv[0], ranks, all.size(), passed_on);
    if (!spread) {
      std::cerr << "monocular_accuracy: a case failed on the MPI ranks (above); nothing written\n";
      return 1;
    }
    rows = std::move(*spread);
  } else {
    Setup setup{sensor::load_photometric_calibration(kSource + "/sample_clouds/gelsight_ball/photometric_calibration.yaml"),
#ifdef TOUCHCLOUD_WITH_NETWORKS
                nullptr,
#endif
                simulation::load_scene(kSource + "/sample_clouds/gelsight_ball/scene.yaml")};
#ifdef TOUCHCLOUD_WITH_NETWORKS
    torch::set_num_threads(1);  // accuracy only; one thread measured fastest on 2 shared cores
    setup.nets = std::make_unique<learning::TactileNetPair>(contact_net, depth_net);
#endif
    // Every press descends at 0.04 mm per frame from the first frame: no fast
    // approach overshooting the press depth.
    setup.scene.robot.approach_speed_mm_s = 0;
    if (noise > 0) {
      setup.scene.effects.add(simulation::Effect::PixelNoise);
      setup.scene.effect_parameters.noise_sigma_grey = noise;
    }
    for (std::size_t i = 0; i < all.size(); ++i)
      if (only_case < 0 || static_cast<long>(i) == only_case) rows.push_back(case_rows(all[i], setup));
    if (only_case >= 0) {
      touchcloud::write_file(rows_file, rows.front());
      return 0;
    }
  }
  std::ostringstream table;
  table << "| object | press (mm) | contact px | method | height RMSE (mm) | max error (mm) | contact IoU | contact F1 |\n"
        << "|---|---|---|---|---|---|---|---|\n";
  for (const std::string& r : rows) table << r;
  std::ostringstream text;
  text << "# Classical depth (photometric_depth) and ContactNet/TactileDepthNet on held-out presses\n\n"
       << "Simulated GelSight Mini-like sensor (320 x 240 px, 0.06 mm/px), calibration from nine presses of a 4 mm "
          "ball; each object pressed once, the given depth past first contact at 0.04 mm per frame (truth contact: true "
          "height > 0.05 mm); pixel noise sigma "
       << noise << " grey levels.\n"
#ifdef TOUCHCLOUD_WITH_NETWORKS
       << "Networks: ContactNet `" << std::filesystem::path(contact_net).filename().string() << "` and TactileDepthNet `"
       << std::filesystem::path(depth_net).filename().string()
       << "` (models/), trained on the indenter board (sample_clouds/gelsight_board/), contact where the probability > 0.5.\n"
#endif
       << "`build/benchmarks/bin/monocular_accuracy --noise " << noise << "`\n\n"
       << table.str();
  std::cout << text.str();
  if (!out.empty()) {
    // The folder made if missing; a failed write is an error, not a "wrote" with no file.
    std::filesystem::create_directories(out);
    const std::string file = out + "/results" + (noise > 0 ? "_noise" : "") + ".md";
    touchcloud::write_file(file, text.str());
    std::cout << "wrote " << file << "\n";
  }
  return 0;
}

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {  // a missing checkpoint or calibration, a bad number
    std::cerr << "monocular_accuracy: " << e.what() << "\n";
    return 1;
  }
}
