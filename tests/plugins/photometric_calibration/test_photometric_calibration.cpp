// photometric_calibration on simulated presses of the shipped ball: the fitted
// polynomial gives the ball's gradients back, the file names its sensor and
// image size, and the stage refuses what it cannot use.
#include <gtest/gtest.h>

#include "ball_calibration.hpp"
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/imaging/ball_press.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/types/frame_stamp.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

TEST(PhotometricCalibration, BallPressesGiveTheBallsGradientsBack) {
  TempDir dir;
  const auto file = calibrate_on_ball(dir, {{-1.5, -1.0}, {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}});
  const auto c = sensor::load_photometric_calibration(file);
  EXPECT_EQ(c.sensor, "gelsight_mini");
  EXPECT_EQ(c.width_px, 320);
  EXPECT_EQ(c.height_px, 240);
  EXPECT_DOUBLE_EQ(c.mm_per_px, 0.06);
  EXPECT_DOUBLE_EQ(c.gel_thickness_mm, 2.5);
  EXPECT_EQ(c.gx.size(), 20u);
  EXPECT_GT(c.samples, 4 * 5000);
  EXPECT_GT(c.max_slope, 0.5);
  std::cout << "calibration: " << c.samples << " samples, residual rms " << c.rms_gradient << ", steepest "
            << c.max_slope << "\n";
  // Residual: 8-bit colours and the ball mesh's 0.05 mm facets.
  EXPECT_LT(c.rms_gradient, 0.02);
  // The flat gel's colour gives no slope.
  EXPECT_LT(c.gradient(Eigen::Vector3d::Zero()).norm(), 0.01);
}

TEST(PhotometricCalibration, RefusesImagesOfAnotherSensorAndRunsWithoutPresses) {
  TempDir dir;
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  StageHarness stage("photometric_calibration",
                     {{"sensor", (source_dir() / "sample_clouds/gelsight_ball/scene.yaml").string()}}, "calibrate",
                     settings);
  stage.configure();
  auto frame = [](int width, const std::string& sensor) {
    auto f = std::make_shared<MonoColourFrame>();
    f->image = cv::Mat(240, width, CV_8UC3, cv::Scalar::all(100));
    f->sensor = sensor;
    return MonoColourFramePtr(f);
  };
  const std::string other = input_error_of([&] {
    stage.process({{"image", frame(320, "gelsight_r15")}, {"reference", frame(320, "gelsight_mini")}}, {});
  });
  EXPECT_NE(other.find("'gelsight_r15'"), std::string::npos) << other;
  EXPECT_NE(other.find("'gelsight_mini'"), std::string::npos) << other;
  const std::string size = input_error_of([&] {
    stage.process({{"image", frame(160, "gelsight_mini")}, {"reference", frame(320, "gelsight_mini")}}, {});
  });
  EXPECT_NE(size.find("160 x 240 px"), std::string::npos) << size;
  EXPECT_NE(size.find("320 x 240"), std::string::npos) << size;
  // A frame without a press is skipped; a run with none fails at the end.
  stage.process({{"image", frame(320, "gelsight_mini")}, {"reference", frame(320, "gelsight_mini")}}, {});
  const std::string none = input_error_of([&] { stage.finish(); });
  EXPECT_NE(none.find("none of the 1 frames shows a ball press"), std::string::npos) << none;
  EXPECT_FALSE(std::filesystem::exists(dir / "photometric_calibration.yaml"));
}

TEST(PhotometricCalibration, TheSensorMustBeOfFamilyGelSight) {
  StageHarness stage("photometric_calibration",
                     {{"sensor", (source_dir() / "sample_clouds/fox_mask/scene.yaml").string()}});
  std::string message;
  try {
    stage.configure();
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("family: gelsight"), std::string::npos) << message;
}

namespace {

// A stage on the shipped ball's sensor writing into `dir`, with `extra` parameters.
std::unique_ptr<StageHarness> ball_stage(const TempDir& dir, std::map<std::string, ParamValue> extra = {}) {
  RunSettings settings;
  settings.staging_dir = dir.path();
  settings.quiet = true;
  extra.emplace("sensor", (source_dir() / "sample_clouds/gelsight_ball/scene.yaml").string());
  auto stage = std::make_unique<StageHarness>("photometric_calibration", extra, "calibrate", settings);
  stage->configure();
  return stage;
}

MonoColourFramePtr colour(cv::Mat image) {
  auto f = std::make_shared<MonoColourFrame>();
  f->image = std::move(image);
  return f;
}

// Feeds `image` named `name` (as image_reader's stamp names it).
void feed(const std::unique_ptr<StageHarness>& stage, const cv::Mat& image, const cv::Mat& reference, const std::string& name) {
  stage->process({{"image", colour(image)}, {"reference", colour(reference)}, {"stamp", FrameStamp{0, 0, name}}}, {});
}

// The reference with a disc `lift` grey levels brighter (a press of a flat-topped indenter).
cv::Mat disc_on(const cv::Mat& reference, cv::Point centre, int radius, int lift = 30) {
  cv::Mat image = reference.clone();
  cv::Mat disc = cv::Mat::zeros(reference.size(), CV_8UC1);
  cv::circle(disc, centre, radius, cv::Scalar(255), cv::FILLED);
  cv::add(image, cv::Scalar::all(lift), image, disc);
  return image;
}

// Four presses of the ball, as the shipped scene makes them.
struct BallPresses {
  std::vector<cv::Mat> images;
  cv::Mat reference;
  BallPresses() {
    simulation::GelSightSimulation sim(ball_scene(), 1);
    for (const Eigen::Vector2d xy : {Eigen::Vector2d(-1.5, -1.0), {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}}) {
      press_pad_into(sim, xy, kBallPressMm);
      images.push_back(sim.render().image);
      reference = sim.render_reference().image;
      sim.step(xy, true);
    }
  }
};

const BallPresses& ball_presses() {
  static const BallPresses presses;
  return presses;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST(PhotometricCalibration, EachRefusalIsCountedAndReportedPerImage) {
  TempDir dir;
  auto stage = ball_stage(dir);
  const auto& ball = ball_presses();
  for (std::size_t i = 0; i < ball.images.size(); ++i)
    feed(stage, ball.images[i], ball.reference, "press_" + std::to_string(i) + ".png");
  feed(stage, ball.reference, ball.reference, "nothing.png");
  feed(stage, disc_on(ball.reference, {12, 120}, 30), ball.reference, "edge.png");
  feed(stage, disc_on(ball.reference, {160, 120}, 75), ball.reference, "wide.png");  // 4.5 mm: wider than the ball
  stage->finish();
  EXPECT_EQ(stage->metric("presses"), 4);
  EXPECT_EQ(stage->metric("frames_skipped"), 3);
  EXPECT_EQ(stage->metric("refused_no_contact"), 1);
  EXPECT_EQ(stage->metric("refused_touching_border"), 1);
  EXPECT_EQ(stage->metric("refused_too_big"), 1);
  const std::string table = read_text(dir / "ball_presses.csv");
  EXPECT_NE(table.find("nothing.png,refused,,,,,,,,no region differs"), std::string::npos) << table;
  EXPECT_NE(table.find("edge.png,refused,,,,,,,,the pressed region touches the image's border"), std::string::npos);
  EXPECT_NE(table.find("wide.png,refused,,,,,,,,the contact circle (radius 4.49"), std::string::npos) << table;
  EXPECT_NE(table.find("press_3.png,found,fit,"), std::string::npos) << table;
  const cv::Mat sheet = cv::imread((dir / "ball_presses.png").string());
  EXPECT_EQ(sheet.size(), cv::Size(4 * 160, 2 * (120 + 30)));  // seven images in rows of four
  // The caps reconstructed with the calibration, against the 4 mm ball.
  EXPECT_LT(stage->metric("cap_rmse_mm"), 0.06);
  EXPECT_NEAR(stage->metric("ball_radius_fit_mm"), 4.0, 0.1);
}

TEST(PhotometricCalibration, TheEdgeFitFindsACircleWhoseMiddleDiffersTooLittle) {
  // A ring: the region's hole (the cap's flat middle) leaves the edge fit's
  // circle where it is; a disc of the region's area would be smaller.
  const cv::Mat reference(240, 320, CV_8UC3, cv::Scalar(90, 100, 110));
  cv::Mat ring = disc_on(reference, {150, 110}, 40);
  cv::circle(ring, {150, 110}, 20, cv::Scalar(90, 100, 110), cv::FILLED);
  const auto fit = imaging::find_ball_press(ring, reference, 8, 4.0, 0.06);
  ASSERT_TRUE(fit.circle) << fit.why;
  EXPECT_NEAR(fit.circle->centre_px.x(), 150, 0.5);
  EXPECT_NEAR(fit.circle->centre_px.y(), 110, 0.5);
  EXPECT_NEAR(fit.circle->radius_px, 40, 1.0);
  const auto area = imaging::find_ball_press(ring, reference, 8, 4.0, 0.06, imaging::CircleMethod::EqualArea);
  EXPECT_LT(area.circle->radius_px, 36);
}

TEST(PhotometricCalibration, TheEdgeFitFindsTheRimWhereTheDifferenceFallsHalfwayNotBelowDetectGrey) {
  // A contact 50 grey levels bright whose rim (radius 40 px, centre off the
  // pixel grid) the optics blur (Gaussian, sigma 1.2 px): the difference
  // falls below detect_grey (8) about 1.2 px outside the rim, then the
  // 3 x 3 mean widens the region further; halfway down is the rim.
  const cv::Mat reference(240, 320, CV_8UC3, cv::Scalar(90, 100, 110));
  cv::Mat image = reference.clone();
  const double cu = 150.3, cv_ = 110.6, rim = 40, sigma = 1.2;
  for (int v = 0; v < image.rows; ++v)
    for (int u = 0; u < image.cols; ++u) {
      const double lift = 25 * std::erfc((std::hypot(u - cu, v - cv_) - rim) / (sigma * std::sqrt(2.0)));
      image.at<cv::Vec3b>(v, u) += cv::Vec3b::all(static_cast<std::uint8_t>(std::lround(lift)));
    }
  const auto fit = imaging::find_ball_press(image, reference, 8, 4.0, 0.06);
  ASSERT_TRUE(fit.circle) << fit.why;
  EXPECT_NEAR(fit.circle->centre_px.x(), cu, 0.05);
  EXPECT_NEAR(fit.circle->centre_px.y(), cv_, 0.05);
  EXPECT_NEAR(fit.circle->radius_px, rim, 0.1);  // the region's edge alone: 40.9 px
}

TEST(PhotometricCalibration, TheCorrectionFileSetsOrSkipsACircle) {
  TempDir dir;
  write_file(dir / "fix.csv",
             "# image, centre_u_px, centre_v_px, radius_px\n"
             "press_0.png, 100.0, 90.0, 30   # hand-set\n"
             "\n"
             "press_1.png, skip\n"
             "edge.png, 40, 120, 25\n");
  auto stage = ball_stage(dir, {{"corrections", (dir / "fix.csv").string()}, {"holdout", 0.5}});
  const auto& ball = ball_presses();
  for (std::size_t i = 0; i < ball.images.size(); ++i)
    feed(stage, ball.images[i], ball.reference, "press_" + std::to_string(i) + ".png");
  feed(stage, disc_on(ball.reference, {12, 120}, 30), ball.reference, "edge.png");
  stage->finish();
  EXPECT_EQ(stage->metric("presses_corrected"), 2);
  EXPECT_EQ(stage->metric("presses_skipped"), 1);
  EXPECT_EQ(stage->metric("refused_touching_border"), 0);
  EXPECT_EQ(stage->metric("presses"), 4);
  EXPECT_EQ(stage->metric("presses_held_out"), 2);  // the 2nd and 4th of press_0, press_2, press_3, edge
  const std::string table = read_text(dir / "ball_presses.csv");
  EXPECT_NE(table.find("press_0.png,corrected,fit,100,90,30,"), std::string::npos) << table;
  EXPECT_NE(table.find("press_1.png,skipped,,,,,,,,the correction file says skip"), std::string::npos) << table;
  EXPECT_NE(table.find("press_2.png,found,held_out,"), std::string::npos) << table;
  EXPECT_NE(table.find("edge.png,corrected,held_out,40,120,25,"), std::string::npos) << table;
}

TEST(PhotometricCalibration, ABadCorrectionRowIsRefusedNamingFileAndLine) {
  TempDir dir;
  auto refusal = [&](const std::string& rows) {
    write_file(dir / "fix.csv", "# corrections\n" + rows);
    return input_error_of([&] { ball_stage(dir, {{"corrections", (dir / "fix.csv").string()}}); });
  };
  const std::string where = (dir / "fix.csv").string() + ":2";
  for (const auto& [rows, why] : std::vector<std::pair<std::string, std::string>>{
           {"a.png, 10, 20\n", "3 fields"},
           {"a.png, ten, 20, 5\n", "'ten' is not a number"},
           {"a.png, 10, 20, 0\n", "the radius 0 px must be above 0"},
           {"a.png, 10, 20, 70\n", "below the ball's 66.6"},
           {"a.png, 400, 20, 5\n", "outside the 320 x 240 px image"},
           {"a.png, skipp\n", "2 fields"},
           {", skip\n", "no image name"}}) {
    const std::string message = refusal(rows);
    EXPECT_NE(message.find(where), std::string::npos) << message;
    EXPECT_NE(message.find(why), std::string::npos) << rows << " -> " << message;
  }
  const std::string twice = refusal("a.png, skip\nb.png, skip\na.png, 10, 20, 5\n");
  EXPECT_NE(twice.find((dir / "fix.csv").string() + ":4"), std::string::npos) << twice;
  EXPECT_NE(twice.find("named again (first on line 2)"), std::string::npos) << twice;
  // A row naming no image read is refused at the end, before anything is written.
  write_file(dir / "fix.csv", "a.png, skip\nmissing.png, skip\n");
  auto stage = ball_stage(dir, {{"corrections", (dir / "fix.csv").string()}});
  feed(stage, ball_presses().images[0], ball_presses().reference, "a.png");
  feed(stage, ball_presses().images[1], ball_presses().reference, "b.png");
  const std::string unused = input_error_of([&] { stage->finish(); });
  EXPECT_NE(unused.find((dir / "fix.csv").string() + ":2"), std::string::npos) << unused;
  EXPECT_NE(unused.find("image missing.png is not among the 2 images read"), std::string::npos) << unused;
  EXPECT_FALSE(std::filesystem::exists(dir / "photometric_calibration.yaml"));
}
