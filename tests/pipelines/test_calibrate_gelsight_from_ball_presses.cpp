// pipelines/calibrate_gelsight_from_ball_presses.yaml on ball presses the
// simulator renders with what real images have (8-bit, pixel noise, the
// lens's vignetting, a background exposed unlike the presses), written as
// PNG files: the calibration it writes reconstructs held-out presses of other
// indenters (balls of 3 and 6 mm, a rod, raised letters) close to their true
// height maps, and the ball's radius comes back from the reconstructed caps.
// The same with marker dots printed on the gel (the simulator's `markers`),
// masked in the calibration (`calibrate.markers=mask`) and in the
// reconstructions.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ml.hpp>
#include <unordered_map>

#include "test_support.hpp"
#include "touchcloud/imaging/ball_press.hpp"
#include "touchcloud/imaging/dst_poisson.hpp"
#include "touchcloud/plugin_kit/marker_mask_parameters.hpp"
#include "touchcloud/imaging/photometric_depth_solver.hpp"
#include "touchcloud/simulation/gelsight_press.hpp"
#include "touchcloud/simulation/objects/indenters.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {

constexpr double kBallRadiusMm = 4.0;

// The shipped ball-press scene with pixel noise and stronger drift, its mesh
// named from the source tree; the robot descends at its slow speed all the
// way, so a press goes no more than 0.04 mm past the depth asked for (raised
// letters 0.35 mm high are pressed without the gel reaching the table).
simulation::Scene realistic_scene(const test::TempDir& dir, bool markers) {
  std::string text = test::read_file(test::source_dir() / "sample_clouds/gelsight_ball/ball_presses/scene.yaml");
  const auto mesh = text.find("../ball_cap.ply");
  text.replace(mesh, std::string("../ball_cap.ply").size(),
               (test::source_dir() / "sample_clouds/gelsight_ball/ball_cap.ply").string());
  const auto approach = text.find("approach_speed_mm_s: 10");
  text.replace(approach, std::string("approach_speed_mm_s: 10").size(), "approach_speed_mm_s: 0");
  text = text.substr(0, text.find("effects:")) +
         "effects:\n  - contact\n  - render\n  - pixel_noise: {sigma_grey: 1.5}\n"
         "  - vignetting: {fall_off: 0.15}\n  - exposure_drift: {gain: 1.015, offset_grey: 1.5}\n" +
         (markers ? "  - markers: {pitch_mm: 2.0, diameter_mm: 0.5, darkness: 0.7, shift_per_slope_mm: 0.5}\n" : "");
  test::write_file(dir / "scene.yaml", text);
  return simulation::load_scene(dir / "scene.yaml");
}

cv::Mat written_and_read(const cv::Mat& image, const fs::path& file) {
  EXPECT_TRUE(cv::imwrite(file.string(), image));
  return cv::imread(file.string(), cv::IMREAD_COLOR);
}

// A reconstructed press: its height against the truth where the true height
// is above 0.02 mm (the contact; the letters' blurred edges fade out below
// that).
struct Reconstruction {
  cv::Mat image, height_mm;
  HeightMap truth;
  double rmse_mm = 0, worst_mm = 0;
  long contact_px = 0;
  bool off_the_image() const {  // the contact reaches the image's border
    cv::Mat inner = cv::Mat::zeros(truth.height_mm.size(), CV_8UC1);
    inner(cv::Rect(1, 1, inner.cols - 2, inner.rows - 2)).setTo(1);
    return cv::countNonZero(truth.height_mm > 0) > cv::countNonZero((truth.height_mm > 0) & inner);
  }
};

void score_against_truth(Reconstruction& r, const std::string& name) {
  double squared = 0;
  for (int v = 0; v < r.height_mm.rows; ++v)
    for (int u = 0; u < r.height_mm.cols; ++u)
      if (r.truth.height_mm.at<float>(v, u) > 0.02f) {
        const double e = r.height_mm.at<float>(v, u) - r.truth.height_mm.at<float>(v, u);
        squared += e * e;
        ++r.contact_px;
      }
  r.rmse_mm = std::sqrt(squared / std::max(r.contact_px, 1L));
  double worst = 0;  // the largest error anywhere: a dot left in integrates to a bump beside the contact too
  cv::minMaxLoc(cv::abs(r.height_mm - r.truth.height_mm), nullptr, &worst);
  r.worst_mm = worst;
  double deepest = 0;
  cv::minMaxLoc(r.truth.height_mm, nullptr, &deepest);
  std::cout << name << ": height RMSE " << r.rmse_mm << " mm over " << r.contact_px << " contact px (deepest "
            << deepest << " mm), largest error " << r.worst_mm << " mm\n";
}

// Tolerances per case, from what was measured (see the tests), 1.3 to 2
// times the worst error. With dots (0.5 mm, 2 mm apart) masked, the
// calibration takes no sample on a dot's ink, its contact circles read no
// rim across a dot, and each dot's pixel takes the gradients around it in
// the reconstructions (imaging/excluded_pixels.hpp). Measured with dots
// (without): contact circles 0.109-0.123 px wider than the true contact
// (0.115-0.124 px), caps 0.026 / 0.038 mm (0.014 / 0.023 mm), ball radius
// 4.013 / 4.089 mm (3.997 / 4.076 mm), held-out heights at most 0.016 mm
// (0.0125 mm), radii from the caps 1.6-2.8 % small (2.0-2.9 %), largest
// error anywhere 0.068 mm (0.020 mm). The mask is what holds them: with the dots left in
// the held-out images (the calibration's mask kept), the dots that move
// with the gel integrate to bumps, height RMSE 0.035-0.11 mm and largest
// errors 0.47-0.94 mm. These tolerances do not catch dots left unmasked
// everywhere (calibration and reconstructions, `markers: none`): on these
// simulated dots, darkening the shading in the image and the background
// alike, the polynomial fitted over the dots' pixels too reads them as
// little slope, and the figures come out no worse than masked (caps 0.025 /
// 0.036 mm, held-out heights at most 0.0098 mm, largest error 0.048 mm).
// What catches that case is photometric_depth's check: a calibration file
// without `markers: masked` fed images with dots is the finding
// markers_not_calibrated (tests/plugins/photometric_depth/test_marker_mask).
struct MarkersOff {
  static constexpr bool on = false;
  static constexpr double cap_rmse_mm = 0.035, worst_mm = 0.04;
};
struct MarkersOn {
  static constexpr bool on = true;
  static constexpr double cap_rmse_mm = 0.05, worst_mm = 0.12;
};
constexpr double kBallRadiusToleranceMm = 0.12, kHeightRmseMm = 0.025, kRadiusShare = 0.05, kCircleTolerancePx = 0.2;

template <typename Markers>
class CalibrateFromBallPresses : public ::testing::Test {
 protected:
  // The dots' ink in a press and its background, as photometric_depth's
  // and photometric_calibration's `markers: mask` find it; none without.
  static imaging::ExcludedPixels excluded(const cv::Mat& image, const cv::Mat& background) {
    if (!Markers::on) return {};
    imaging::ExcludedPixels e = mask_parameters().make_mask()->masks(image, background).excluded;
    e.mask = e.mask.clone();
    return e;
  }
  static imaging::MarkerMaskParameters mask_parameters() {  // the stages' defaults
    return {imaging::MarkerHandling::Mask, {3, 12}, 20.0};
  }

  // Eight presses of the 4 mm ball over the pad and the background, as PNG
  // files; the shipped pipeline run on them.
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    simulation::GelSightSimulation sim(realistic_scene(*dir_, Markers::on), 47);
    fs::create_directories(*dir_ / "presses");
    contact_radius_px_ = new std::vector<double>;
    int k = 0;
    for (const auto& xy : simulation::ball_press_targets(sim.sensor(), 8, 2.6)) {
      const auto press = simulation::press_and_render(sim, xy, 0.7);
      written_and_read(press.image.image, *dir_ / "presses" / ("press_" + std::to_string(++k) + ".png"));
      double deepest = 0;  // the true contact: the ball's cap that deep
      cv::minMaxLoc(press.truth.height_mm, nullptr, &deepest);
      contact_radius_px_->push_back(std::sqrt(deepest * (2 * kBallRadiusMm - deepest)) / sim.sensor().mm_per_px);
    }
    background_ = new cv::Mat(written_and_read(sim.render_reference().image, *dir_ / "background.png"));
    PluginRegistry registry;
    std::vector<Override> overrides = {{"background.path", (*dir_ / "background.png").string()},
                                       {"read.path", (*dir_ / "presses/*.png").string()}};
    if (Markers::on) overrides.push_back({"calibrate.markers", "mask"});
    Pipeline p = Pipeline::load(test::source_dir() / "pipelines/calibrate_gelsight_from_ball_presses.yaml",
                                overrides, registry);
    RunOptions o;
    o.quiet = true;
    o.out_dir = *dir_ / "out";
    record_ = new RunRecord(run_pipeline(p, o).record);
  }
  static void TearDownTestSuite() {
    delete record_;
    delete contact_radius_px_;
    delete background_;
    delete dir_;
  }
  static double metric(const std::string& name) { return record_->metrics.at("calibrate." + name).values.back(); }

  // A held-out press of `object` (at the base's origin) with the pad's
  // centre at `place_mm`, `travel_mm` deep, through a PNG file and the
  // calibration, against its truth.
  static Reconstruction reconstruct(std::shared_ptr<const simulation::ObjectSurface> object,
                                    const Eigen::Vector2d& place_mm, double travel_mm, const std::string& name,
                                    imaging::PoissonBorder border = imaging::PoissonBorder::Zero) {
    simulation::GelSightSimulation sim(realistic_scene(*dir_, Markers::on), 48, std::move(object));
    auto press = simulation::press_and_render(sim, place_mm, travel_mm);
    Reconstruction r;
    r.image = written_and_read(press.image.image, *dir_ / (name + ".png"));
    imaging::DepthOptions options;
    options.border = border;
    imaging::PhotometricDepthSolver solver(
        sensor::load_photometric_calibration(*dir_ / "out/photometric_calibration.yaml"), options);
    if (Markers::on)  // as photometric_depth's `markers: mask`: the dots' pixels take the gradients around them
      r.height_mm = solver.solve(r.image, *background_, excluded(r.image, *background_)).height_mm;
    else
      r.height_mm = solver.solve(r.image, *background_).height_mm;
    r.truth = press.truth;
    score_against_truth(r, name);
    return r;
  }

  static test::TempDir* dir_;
  static cv::Mat* background_;
  static RunRecord* record_;
  static std::vector<double>* contact_radius_px_;  // press_k.png's true contact, k from 1
};
template <typename Markers>
test::TempDir* CalibrateFromBallPresses<Markers>::dir_ = nullptr;
template <typename Markers>
cv::Mat* CalibrateFromBallPresses<Markers>::background_ = nullptr;
template <typename Markers>
RunRecord* CalibrateFromBallPresses<Markers>::record_ = nullptr;
template <typename Markers>
std::vector<double>* CalibrateFromBallPresses<Markers>::contact_radius_px_ = nullptr;

using MarkerCases = ::testing::Types<MarkersOff, MarkersOn>;
TYPED_TEST_SUITE(CalibrateFromBallPresses, MarkerCases);

}  // namespace

TYPED_TEST(CalibrateFromBallPresses, FindsEveryPressAndGivesTheBallsRadiusBack) {
  const auto metric = [](const std::string& name) { return TestFixture::metric(name); };
  auto* dir_ = TestFixture::dir_;
  EXPECT_EQ(metric("presses"), 8);
  EXPECT_EQ(metric("presses_held_out"), 2);
  EXPECT_EQ(metric("frames_skipped"), 0);
  std::cout << "cap RMSE " << metric("cap_rmse_mm") << " mm fitted, " << metric("holdout_cap_rmse_mm")
            << " mm held out; ball radius " << metric("ball_radius_fit_mm") << " mm fitted, "
            << metric("holdout_ball_radius_fit_mm") << " mm held out\n";
  // Measured: see the tolerances; the outer presses, where vignetting dims
  // the contact most, are the worst.
  EXPECT_LT(metric("cap_rmse_mm"), TypeParam::cap_rmse_mm);
  EXPECT_LT(metric("holdout_cap_rmse_mm"), TypeParam::cap_rmse_mm);
  EXPECT_NEAR(metric("ball_radius_fit_mm"), kBallRadiusMm, kBallRadiusToleranceMm);
  EXPECT_NEAR(metric("holdout_ball_radius_fit_mm"), kBallRadiusMm, kBallRadiusToleranceMm);
  // Each circle against the true contact (ball_presses.csv: image, status,
  // role, centre u, v, radius px, ...). The pressed region's edge lies about
  // a pixel outside the rim (where the difference falls below detect_grey),
  // which made the ideal caps the circles give 0.04 mm too deep; a rim read
  // across a dot's filled pixels lies 0.1 px further out.
  std::istringstream table(test::read_file(dir_->path() / "out/ball_presses.csv"));
  std::string line;
  std::getline(table, line);
  int rows = 0;
  while (std::getline(table, line)) {
    std::vector<std::string> field;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) field.push_back(cell);
    ASSERT_GE(field.size(), 6u) << line;
    const int k = std::stoi(field[0].substr(std::string("press_").size()));
    const double truth = TestFixture::contact_radius_px_->at(k - 1);
    std::cout << field[0] << ": contact radius " << field[5] << " px, true " << truth << " px\n";
    EXPECT_NEAR(std::stod(field[5]), truth, kCircleTolerancePx) << field[0];
    ++rows;
  }
  EXPECT_EQ(rows, 8);
  EXPECT_TRUE(fs::exists(dir_->path() / "out/ball_presses.csv"));
  EXPECT_TRUE(fs::exists(dir_->path() / "out/ball_presses.png"));
}

TYPED_TEST(CalibrateFromBallPresses, ReconstructsHeldOutIndentersWithinTolerance) {
  const cv::Mat* background_ = TestFixture::background_;
  // Each indenter pressed with the pad's centre over it and 2.5 mm to one
  // side, 2 mm to the other (the contact off the image's centre, where the
  // vignetting dims it; off-centre errors were at most 0.008 mm without
  // dots, 0.016 mm with). Further off: the next test.
  // Measured height RMSE in the contact without dots: 0.010 mm (3 mm ball),
  // 0.013 mm (6 mm ball), 0.006 mm (rod), 0.002 mm (letters) at the centre,
  // on contacts 0.32-0.68 mm deep; the tolerance, 0.025 mm (under 8 % of the
  // shallowest), is twice the worst without dots, 1.5 times with. Balls of other radii: the
  // radius from a sphere fitted to the reconstructed cap in the circle the
  // finder gives came back 2.5-3 % small: within 5 %.
  for (const auto& [name, place] : {std::pair{std::string("centre"), Eigen::Vector2d(0, 0)},
                                    std::pair{std::string("off_centre"), Eigen::Vector2d(2.5, -2.0)}}) {
    const auto check = [&](const Reconstruction& r, const std::string& what) {
      EXPECT_LT(r.rmse_mm, kHeightRmseMm) << what << " at the " << name;
      EXPECT_LT(r.worst_mm, TypeParam::worst_mm) << what << " at the " << name;
    };
    for (const auto& [radius, travel] : {std::pair{3.0, 0.5}, std::pair{6.0, 0.6}}) {
      const std::string what = "ball_" + std::to_string(int(radius)) + "_" + name;
      const auto r = TestFixture::reconstruct(
          std::make_shared<simulation::BallIndenter>(radius, Eigen::Vector2d::Zero(), 8.0), place, travel, what);
      check(r, what);
      const auto found = imaging::find_ball_press(r.image, *background_, TestFixture::excluded(r.image, *background_),
                                                  8, radius, 0.06);
      ASSERT_TRUE(found.circle) << found.why;
      const auto cap = imaging::score_ball_cap(r.height_mm, *found.circle, radius, 0.06);
      std::cout << "  radius from its cap " << cap.fitted_radius_mm << " mm\n";
      EXPECT_NEAR(cap.fitted_radius_mm, radius, kRadiusShare * radius) << what;
    }
    check(TestFixture::reconstruct(
              std::make_shared<simulation::RodIndenter>(2.5, Eigen::Vector2d(-3, 0), Eigen::Vector2d(3, 0), 8.0),
              place, 0.5, "rod_" + name),
          "rod");
    check(TestFixture::reconstruct(
              std::make_shared<simulation::TextRelief>("TC", 6.0, 0.6, 0.35, 0.25, Eigen::Vector2d::Zero()), place,
              0.25, "text_" + name),
          "letters");
  }
}


TYPED_TEST(CalibrateFromBallPresses, ReconstructsIndentersFarOffCentre) {
  // The pad's centre 4 mm and -3 mm off each indenter: the contact near the
  // image's corner, where the vignetting dims it most. Measured height RMSE
  // without dots (with): 3 mm ball 0.0029 mm (0.0029), 6 mm ball 0.0023 mm
  // (0.015), rod 0.011 mm (0.019); largest errors 0.012-0.026 mm
  // (0.013-0.050). There the marker detector loses, in the image, dots that
  // the press moved within the contact's dark upper side (1 and 5 of the 63
  // it finds in the background); the mask looks for their ink near their
  // rest places (imaging/marker_mask.hpp), without which it stays in and
  // integrates to bumps: 3 mm ball 0.047 mm, largest error 0.24 mm; rod
  // 0.068 mm, 0.52 mm.
  const Eigen::Vector2d place(4.0, -3.0);
  const auto check = [](const Reconstruction& r, const std::string& what) {
    EXPECT_FALSE(r.off_the_image()) << what;
    EXPECT_LT(r.rmse_mm, kHeightRmseMm) << what;
    EXPECT_LT(r.worst_mm, TypeParam::worst_mm) << what;
  };
  for (const auto& [radius, travel] : {std::pair{3.0, 0.5}, std::pair{6.0, 0.6}})
    check(TestFixture::reconstruct(std::make_shared<simulation::BallIndenter>(radius, Eigen::Vector2d::Zero(), 8.0),
                                   place, travel, "ball_" + std::to_string(int(radius)) + "_far_off"),
          "ball of " + std::to_string(int(radius)) + " mm");
  check(TestFixture::reconstruct(
            std::make_shared<simulation::RodIndenter>(2.5, Eigen::Vector2d(-3, 0), Eigen::Vector2d(3, 0), 8.0), place,
            0.5, "rod_far_off"),
        "rod");
  // The letters run off the image. The default integration holds the
  // image's border at zero height and pulls the letters down to it: height
  // RMSE 0.116 mm (0.124 mm with dots), largest error 0.28 mm (0.29 mm).
  // photometric_depth's `border: free` (the height's zero on the flat
  // pixels) is the answer there: 0.0052 mm (0.016 mm), largest error
  // 0.017 mm (0.063 mm).
  const auto letters = [&](imaging::PoissonBorder border, const std::string& name) {
    return TestFixture::reconstruct(
        std::make_shared<simulation::TextRelief>("TC", 6.0, 0.6, 0.35, 0.25, Eigen::Vector2d::Zero()), place, 0.25,
        name, border);
  };
  const auto zero = letters(imaging::PoissonBorder::Zero, "text_far_off");
  EXPECT_TRUE(zero.off_the_image());
  EXPECT_GT(zero.rmse_mm, 0.08);
  const auto free = letters(imaging::PoissonBorder::Free, "text_far_off_free_border");
  EXPECT_LT(free.rmse_mm, kHeightRmseMm);
  EXPECT_LT(free.worst_mm, TypeParam::worst_mm);
}

namespace {

// A binned lookup table from colour difference to gradient, as gs_sdk and
// Taxim calibrate: the mean gradient of the samples in each cube of
// `bin_grey` grey levels of (R, G, B) difference; an empty cube takes the
// mean of its filled neighbours (repeated until every cube is filled); a
// difference beyond the table takes its nearest cube. Only to compare with
// the polynomial (docs/sensors/gelsight.md, "Polynomial or lookup table").
class LookupTable {
 public:
  LookupTable(const std::vector<Eigen::Vector3d>& difference, const std::vector<Eigen::Vector2d>& gradient,
              double bin_grey)
      : bin_(bin_grey) {
    Eigen::Vector3i high = Eigen::Vector3i::Constant(-(1 << 20));
    low_.setConstant(1 << 20);
    for (const auto& d : difference)
      for (int c = 0; c < 3; ++c) {
        low_[c] = std::min(low_[c], cell(d[c]));
        high[c] = std::max(high[c], cell(d[c]));
      }
    size_ = high - low_ + Eigen::Vector3i::Ones();
    gradient_.assign(size_.prod(), Eigen::Vector2d::Zero());
    std::vector<int> count(gradient_.size(), 0);
    for (std::size_t i = 0; i < difference.size(); ++i) {
      gradient_[index(difference[i])] += gradient[i];
      ++count[index(difference[i])];
    }
    std::vector<char> filled(gradient_.size());
    for (std::size_t i = 0; i < gradient_.size(); ++i)
      if ((filled[i] = count[i] > 0)) gradient_[i] /= count[i];
    for (bool growing = true; growing;) {
      growing = false;
      std::vector<char> next = filled;
      std::vector<Eigen::Vector2d> grown = gradient_;
      for (int a = 0; a < size_[0]; ++a)
        for (int b = 0; b < size_[1]; ++b)
          for (int c = 0; c < size_[2]; ++c) {
            const int i = flat({a, b, c});
            if (filled[i]) continue;
            Eigen::Vector2d sum = Eigen::Vector2d::Zero();
            int n = 0;
            for (const Eigen::Vector3i& step : {Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(-1, 0, 0), Eigen::Vector3i(0, 1, 0),
                                               Eigen::Vector3i(0, -1, 0), Eigen::Vector3i(0, 0, 1), Eigen::Vector3i(0, 0, -1)}) {
              const Eigen::Vector3i k = Eigen::Vector3i(a, b, c) + step;
              if ((k.array() < 0).any() || (k.array() >= size_.array()).any() || !filled[flat(k)]) continue;
              sum += gradient_[flat(k)];
              ++n;
            }
            if (n == 0) continue;
            grown[i] = sum / n;
            next[i] = growing = true;
          }
      gradient_ = std::move(grown);
      filled = std::move(next);
    }
  }
  Eigen::Vector2d operator()(const Eigen::Vector3d& difference) const { return gradient_[index(difference)]; }

 private:
  int cell(double grey) const { return static_cast<int>(std::floor(grey / bin_)); }
  int flat(const Eigen::Vector3i& k) const { return (k[0] * size_[1] + k[1]) * size_[2] + k[2]; }
  int index(const Eigen::Vector3d& d) const {
    Eigen::Vector3i k;
    for (int c = 0; c < 3; ++c) k[c] = std::clamp(cell(d[c]) - low_[c], 0, size_[c] - 1);
    return flat(k);
  }
  double bin_;
  Eigen::Vector3i low_, size_;
  std::vector<Eigen::Vector2d> gradient_;
};

// A small network from colour difference to gradient (OpenCV's multilayer
// perceptron: 3 inputs, two hidden layers of `hidden` symmetric sigmoids,
// 2 outputs, trained by RPROP from a seeded start), as learned calibrations
// map colour to gradient; fitted to the same samples. Only to compare with
// the polynomial. A pixel's difference is looked up once per image.
class SmallNetwork {
 public:
  SmallNetwork(const std::vector<Eigen::Vector3d>& difference, const std::vector<Eigen::Vector2d>& gradient, int hidden)
      : net_(cv::ml::ANN_MLP::create()) {
    constexpr int kSamples = 4000, kIterations = 1000;
    const int every = std::max<int>(1, static_cast<int>(difference.size()) / kSamples);  // every k-th sample
    cv::Mat in(static_cast<int>(difference.size()) / every, 3, CV_32FC1), out(in.rows, 2, CV_32FC1);
    for (int i = 0; i < in.rows; ++i) {
      for (int c = 0; c < 3; ++c) in.at<float>(i, c) = static_cast<float>(difference[i * every][c]);
      for (int c = 0; c < 2; ++c) out.at<float>(i, c) = static_cast<float>(gradient[i * every][c]);
    }
    const auto start = std::chrono::steady_clock::now();
    net_->setLayerSizes(std::vector<int>{3, hidden, hidden, 2});
    net_->setActivationFunction(cv::ml::ANN_MLP::SIGMOID_SYM);
    net_->setTrainMethod(cv::ml::ANN_MLP::RPROP);
    net_->setTermCriteria(cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, kIterations, 1e-7));
    cv::theRNG().state = 1;  // the weights' start
    net_->train(cv::ml::TrainData::create(in, cv::ml::ROW_SAMPLE, out));
    std::cout << "network 2 x " << hidden << ": " << in.rows << " of " << difference.size() << " samples, "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  }
  Eigen::Vector2d operator()(const Eigen::Vector3d& d) const {
    const long key = ((static_cast<long>(d[0]) + 256) * 512 + static_cast<long>(d[1]) + 256) * 512 + static_cast<long>(d[2]) + 256;
    if (auto known = seen_.find(key); known != seen_.end()) return known->second;
    cv::Mat in = (cv::Mat_<float>(1, 3) << static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]));
    cv::Mat out;
    net_->predict(in, out);
    return seen_[key] = Eigen::Vector2d(out.at<float>(0, 0), out.at<float>(0, 1));
  }

 private:
  cv::Ptr<cv::ml::ANN_MLP> net_;
  mutable std::unordered_map<long, Eigen::Vector2d> seen_;
};

// The height photometric_depth integrates (flat pixels, the dots' fill,
// zero border) with any mapping from colour difference to gradient.
cv::Mat height_through(const std::function<Eigen::Vector2d(const Eigen::Vector3d&)>& mapping, const cv::Mat& image,
                       const cv::Mat& reference, const imaging::ExcludedPixels& excluded, double mm_per_px) {
  const int w = image.cols, h = image.rows, flat_grey = static_cast<int>(imaging::DepthOptions{}.flat_grey);
  cv::Mat gx(h, w, CV_64FC1), gy(h, w, CV_64FC1);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const cv::Vec3b a = image.at<cv::Vec3b>(v, u), b = reference.at<cv::Vec3b>(v, u);
      const Eigen::Vector3d d(a[2] - b[2], a[1] - b[1], a[0] - b[0]);
      const Eigen::Vector2d g = d.cwiseAbs().maxCoeff() <= flat_grey ? Eigen::Vector2d::Zero() : mapping(d);
      gx.at<double>(v, u) = g.x();
      gy.at<double>(v, u) = g.y();
    }
  if (!excluded.mask.empty()) imaging::ExcludedFill().fill(excluded, {&gx, &gy});
  cv::Mat p(h, w - 1, CV_64FC1), q(h - 1, w, CV_64FC1);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u + 1 < w; ++u) p.at<double>(v, u) = 0.5 * (gx.at<double>(v, u) + gx.at<double>(v, u + 1)) * mm_per_px;
  for (int v = 0; v + 1 < h; ++v)
    for (int u = 0; u < w; ++u) q.at<double>(v, u) = 0.5 * (gy.at<double>(v, u) + gy.at<double>(v + 1, u)) * mm_per_px;
  cv::Mat height;
  imaging::DstPoisson(w, h).solve(p, q).convertTo(height, CV_32FC1);
  return height;
}

double contact_rmse_mm(const cv::Mat& height_mm, const cv::Mat& truth_mm) {
  double squared = 0;
  long n = 0;
  for (int v = 0; v < height_mm.rows; ++v)
    for (int u = 0; u < height_mm.cols; ++u)
      if (truth_mm.at<float>(v, u) > 0.02f) {
        const double e = height_mm.at<float>(v, u) - truth_mm.at<float>(v, u);
        squared += e * e;
        ++n;
      }
  return std::sqrt(squared / n);
}

}  // namespace

// A lookup table and a small network fitted to the same samples as the
// polynomial, on the same held-out presses. The table is better on the
// 3 mm ball, no better on the 6 mm ball and the letters, 2-3 times worse on
// the rod, whose rim is steeper than any sample of the 4 mm ball's caps
// (inside 0.9 of the contact): it holds its outermost cube there, where the
// polynomial goes on. The networks are better on some presses and worse on
// the 6 mm ball and the rod. The worst held-out error of each is the larger
// with and without dots, so the polynomial stays (the table in
// docs/sensors/gelsight.md is this test's output).
TYPED_TEST(CalibrateFromBallPresses, NeitherALookupTableNorASmallNetworkIsBetterThanThePolynomial) {
  const cv::Mat& background = *TestFixture::background_;
  const fs::path out = TestFixture::dir_->path() / "out";
  const auto polynomial = sensor::load_photometric_calibration(out / "photometric_calibration.yaml");
  std::vector<Eigen::Vector3d> difference;
  std::vector<Eigen::Vector2d> gradient;
  std::istringstream table(test::read_file(out / "ball_presses.csv"));
  std::string line;
  std::getline(table, line);
  while (std::getline(table, line)) {  // the fitted presses' samples, as the stage took them
    std::vector<std::string> field;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) field.push_back(cell);
    if (field.at(2) != "fit") continue;
    const cv::Mat image = cv::imread((TestFixture::dir_->path() / "presses" / field[0]).string());
    const imaging::ContactCircle circle{{std::stod(field[3]), std::stod(field[4])}, std::stod(field[5])};
    imaging::ball_samples(image, background, TestFixture::excluded(image, background).mask, circle, kBallRadiusMm,
                          polynomial.mm_per_px, difference, gradient);
  }
  EXPECT_EQ(static_cast<long>(difference.size()), polynomial.samples);
  const std::vector<double> bins = {4.0, 8.0};
  std::vector<LookupTable> tables;
  for (double bin : bins) tables.emplace_back(difference, gradient, bin);
  const std::vector<int> widths = {8, 16};
  std::vector<SmallNetwork> networks;
  for (int hidden : widths) networks.emplace_back(difference, gradient, hidden);
  std::vector<double> worst_per_network(widths.size(), 0.0);

  double worst_polynomial = 0, worst_table = 1e9;
  std::vector<double> worst_per_table(bins.size(), 0.0);
  std::cout << "held-out press | polynomial";
  for (double bin : bins) std::cout << " | table, " << bin << " grey bins";
  for (int hidden : widths) std::cout << " | network, 2 x " << hidden;
  std::cout << "\n";
  const auto compare = [&](std::shared_ptr<const simulation::ObjectSurface> object, const Eigen::Vector2d& place,
                           double travel, const std::string& name) {
    const Reconstruction r = TestFixture::reconstruct(object, place, travel, name);
    const auto excluded = TestFixture::excluded(r.image, background);
    const cv::Mat through_polynomial = height_through([&](const Eigen::Vector3d& d) { return polynomial.gradient(d); },
                                                      r.image, background, excluded, polynomial.mm_per_px);
    // The same integration as photometric_depth's: the same heights.
    EXPECT_LT(cv::norm(through_polynomial, r.height_mm, cv::NORM_INF), 1e-4) << name;
    worst_polynomial = std::max(worst_polynomial, r.rmse_mm);
    std::cout << name << " | " << r.rmse_mm;
    for (std::size_t t = 0; t < tables.size(); ++t) {
      const double rmse = contact_rmse_mm(
          height_through(tables[t], r.image, background, excluded, polynomial.mm_per_px), r.truth.height_mm);
      worst_per_table[t] = std::max(worst_per_table[t], rmse);
      std::cout << " | " << rmse;
    }
    for (std::size_t n = 0; n < networks.size(); ++n) {
      const double rmse = contact_rmse_mm(
          height_through(networks[n], r.image, background, excluded, polynomial.mm_per_px), r.truth.height_mm);
      worst_per_network[n] = std::max(worst_per_network[n], rmse);
      std::cout << " | " << rmse;
    }
    std::cout << "\n";
  };
  for (const auto& [name, place] : {std::pair{std::string("centre"), Eigen::Vector2d(0, 0)},
                                    std::pair{std::string("off_centre"), Eigen::Vector2d(2.5, -2.0)}}) {
    for (const auto& [radius, travel] : {std::pair{3.0, 0.5}, std::pair{6.0, 0.6}})
      compare(std::make_shared<simulation::BallIndenter>(radius, Eigen::Vector2d::Zero(), 8.0), place, travel,
              "ball_" + std::to_string(int(radius)) + "_" + name);
    compare(std::make_shared<simulation::RodIndenter>(2.5, Eigen::Vector2d(-3, 0), Eigen::Vector2d(3, 0), 8.0), place,
            0.5, "rod_" + name);
    compare(std::make_shared<simulation::TextRelief>("TC", 6.0, 0.6, 0.35, 0.25, Eigen::Vector2d::Zero()), place, 0.25,
            "text_" + name);
  }
  for (double w : worst_per_table) worst_table = std::min(worst_table, w);
  const double worst_network = *std::min_element(worst_per_network.begin(), worst_per_network.end());
  std::cout << "worst: polynomial " << worst_polynomial << " mm, best table " << worst_table << " mm, best network "
            << worst_network << " mm\n";
  EXPECT_GT(worst_table, 1.3 * worst_polynomial);
  // Measurably better would be a worst error 10 % below the polynomial's (measured: 19 % and 4 % above it).
  EXPECT_GT(worst_network, 0.9 * worst_polynomial);
}
