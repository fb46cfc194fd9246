// photometric_depth's checks on a ball press rendered by the simulator and
// calibrated from other presses: a clean press passes every check; a
// calibration of a thinner gel, a contact share over the limit and a
// reference of another exposure each warn (metric, note) or, with
// `checks: error`, stop the run naming what was measured.
#include <gtest/gtest.h>

#include "ball_calibration.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"
#include "touchcloud/types/height_map.hpp"
#include "touchcloud/types/mono_colour_frame.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

class DepthChecks : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    calibration_ = new std::filesystem::path(
        calibrate_on_ball(*dir_, {{-1.5, -1.0}, {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}}));
    simulation::GelSightSimulation sim(ball_scene(), 2);
    press_pad_into(sim, {0.4, -0.3}, 0.5);
    image_ = new MonoColourFrame(sim.render());
    reference_ = new MonoColourFrame(sim.render_reference());
  }
  static void TearDownTestSuite() {
    delete image_, delete reference_, delete calibration_, delete dir_;
  }

  // A copy of the calibration with another gel thickness.
  static std::string calibration_with_gel(double thickness_mm) {
    sensor::PhotometricCalibration c = sensor::load_photometric_calibration(*calibration_);
    c.gel_thickness_mm = thickness_mm;
    const auto file = *dir_ / "thin_gel.yaml";
    sensor::write_photometric_calibration(c, file);
    return file.string();
  }

  struct Outcome {
    double warnings = 0, exposure = 0;
    std::map<std::string, std::string> notes;
    std::string error;
  };
  static Outcome depth(std::map<std::string, ParamValue> params, const MonoColourFrame& reference = *reference_) {
    if (!params.count("calibration")) params["calibration"] = calibration_->string();
    StageHarness stage("photometric_depth", params, "depth");
    stage.configure();
    Outcome o;
    try {
      stage.process({{"image", MonoColourFramePtr(std::make_shared<MonoColourFrame>(*image_))},
                     {"reference", MonoColourFramePtr(std::make_shared<MonoColourFrame>(reference))}},
                    {"height"});
    } catch (const InputError& e) {
      o.error = e.what();
      return o;
    }
    o.warnings = stage.metric("depth_warnings");
    o.exposure = stage.metric("exposure_difference_grey");
    o.notes = stage.record().notes;
    return o;
  }

  static inline TempDir* dir_ = nullptr;
  static inline std::filesystem::path* calibration_ = nullptr;
  static inline MonoColourFrame *image_ = nullptr, *reference_ = nullptr;
};

}  // namespace

TEST_F(DepthChecks, ACleanPressPassesEveryCheck) {
  const Outcome o = depth({});
  EXPECT_EQ(o.error, "");
  EXPECT_EQ(o.warnings, 0);
  EXPECT_LT(std::abs(o.exposure), 1.0);
  EXPECT_EQ(o.notes.count("depth.height_over_gel") + o.notes.count("depth.contact_everywhere") +
                o.notes.count("depth.exposure_mismatch"),
            0u);
}

TEST_F(DepthChecks, AHeightBeyondTheGelsThicknessWarnsOrStops) {
  const std::string thin = calibration_with_gel(0.2);
  const Outcome warned = depth({{"calibration", thin}});
  EXPECT_EQ(warned.warnings, 1);
  ASSERT_TRUE(warned.notes.count("depth.height_over_gel"));
  EXPECT_NE(warned.notes.at("depth.height_over_gel").find("more than the gel's thickness 0.2 mm"), std::string::npos)
      << warned.notes.at("depth.height_over_gel");
  const Outcome stopped = depth({{"calibration", thin}, {"checks", std::string("error")}});
  EXPECT_NE(stopped.error.find("more than the gel's thickness 0.2 mm"), std::string::npos) << stopped.error;
  EXPECT_NE(stopped.error.find("(checks: error)"), std::string::npos) << stopped.error;
}

TEST_F(DepthChecks, ContactOverMoreThanTheShareWarnsOrStops) {
  const Outcome warned = depth({{"max_contact_share", 0.005}});
  EXPECT_EQ(warned.warnings, 1);
  ASSERT_TRUE(warned.notes.count("depth.contact_everywhere"));
  EXPECT_NE(warned.notes.at("depth.contact_everywhere").find("% of the image, more than 0.5 %"), std::string::npos)
      << warned.notes.at("depth.contact_everywhere");
  const Outcome stopped = depth({{"max_contact_share", 0.005}, {"checks", std::string("error")}});
  EXPECT_NE(stopped.error.find("contact covers"), std::string::npos) << stopped.error;
}

TEST_F(DepthChecks, AReferenceOfAnotherExposureWarnsOrStops) {
  MonoColourFrame darker = *reference_;
  darker.image = reference_->image - cv::Scalar::all(20);
  const Outcome warned = depth({}, darker);
  EXPECT_GT(warned.exposure, 15);
  ASSERT_TRUE(warned.notes.count("depth.exposure_mismatch"));
  EXPECT_NE(warned.notes.at("depth.exposure_mismatch").find("grey levels brighter than the reference where the gel is flat"),
            std::string::npos)
      << warned.notes.at("depth.exposure_mismatch");
  const Outcome stopped = depth({{"checks", std::string("error")}}, darker);
  EXPECT_NE(stopped.error.find("brighter than the reference"), std::string::npos) << stopped.error;
}
