// contact_mask against the simulator's contact truth on a sphere press, and
// the pairs it refuses.
#include <gtest/gtest.h>

#include <iostream>

#include "colour_fixture.hpp"
#include "sim_fixture.hpp"
#include "stage_harness.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
using simulation::GelStereoSimulation;

TEST(ContactMask, FindsTheSpheresContactAgainstTheReferencePair) {
  TempDir dir;
  write_file(dir / "sphere.obj", sphere_obj(8.0, 2.0));
  GelStereoSimulation s(colour_scene(dir, "{mesh: sphere.obj}", "[contact, render, refraction, pixel_noise]"), 1);
  press_into(s, {0, 0}, 1.5);
  const auto frame = std::make_shared<ColourStereoFrame>(s.render_colour());
  const auto reference = std::make_shared<ColourStereoFrame>(s.render_colour_reference());
  const DenseMaps truth = s.dense_truth();
  StageHarness h("contact_mask", {});
  h.configure();
  const auto mask = h.process_one<DenseMapsPtr>(
      {{"frame", ColourStereoFramePtr(frame)}, {"reference", ColourStereoFramePtr(reference)}}, "mask");
  ASSERT_EQ(mask->contact_mask.size(), truth.contact_mask.size());
  const double both = cv::countNonZero(mask->contact_mask & truth.contact_mask);
  const double either = cv::countNonZero(mask->contact_mask | truth.contact_mask);
  std::cout << "sphere press: mask " << cv::countNonZero(mask->contact_mask) << " px, truth "
            << cv::countNonZero(truth.contact_mask) << " px, intersection over union " << both / either << "\n";
  // The pressed pattern moves by about a pixel along the cameras' rays; with
  // pixel noise of 2 grey levels the default threshold finds most of it
  // (measured: 0.84).
  EXPECT_GT(both / either, 0.75);

}

TEST(ContactMask, RefusesFramesThatDoNotMatchTheirReference) {
  StageHarness h("contact_mask", {});
  h.configure();
  auto pair = [](int width, int type) {
    auto f = std::make_shared<ColourStereoFrame>();
    f->left = cv::Mat(40, width, type, cv::Scalar::all(10));
    f->right = f->left.clone();
    return ColourStereoFramePtr(f);
  };
  auto message = [&](ColourStereoFramePtr frame, ColourStereoFramePtr reference) {
    try {
      h.process({{"frame", frame}, {"reference", reference}}, {"mask"});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "accepted";
    return std::string();
  };
  const std::string size = message(pair(64, CV_8UC3), pair(32, CV_8UC3));
  EXPECT_NE(size.find("64 x 40"), std::string::npos) << size;
  EXPECT_NE(size.find("32 x 40"), std::string::npos) << size;
  EXPECT_NE(message(pair(64, CV_8UC3), pair(64, CV_8UC1)).find("CV_8UC1"), std::string::npos);
  auto empty = std::make_shared<ColourStereoFrame>();
  EXPECT_NE(message(empty, pair(64, CV_8UC3)).find("input 'frame': the left image is empty"), std::string::npos);
}
