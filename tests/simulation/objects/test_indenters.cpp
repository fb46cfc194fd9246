// The indenters of GelSight-type presses: a ball's and a rod's round tops
// against their formulas, raised letters with their relief where the ink is
// and the table around them; and presses of them at a set depth.
#include <gtest/gtest.h>

#include <cmath>

#include "gelsight_fixture.hpp"
#include "sim_fixture.hpp"
#include "touchcloud/simulation/gelsight_press.hpp"
#include "touchcloud/simulation/objects/indenters.hpp"

using namespace touchcloud;
using namespace touchcloud::simulation;

TEST(Indenters, BallAndRodHaveRoundTopsAndTheTableAround) {
  const BallIndenter ball(3.0, {1, 2}, 8.0);
  EXPECT_DOUBLE_EQ(ball.height_mm({1, 2}), 8.0);
  EXPECT_NEAR(ball.height_mm({2, 2}), 8.0 - 3.0 + std::sqrt(8.0), 1e-12);
  EXPECT_EQ(ball.height_mm({5, 2}), 0.0);
  EXPECT_EQ(ball.max_height_mm({20, 20}, 1), 8.0);  // an upper bound anywhere
  const RodIndenter rod(2.0, {-3, 0}, {3, 0}, 6.0);
  EXPECT_DOUBLE_EQ(rod.height_mm({-3, 0}), 6.0);
  EXPECT_DOUBLE_EQ(rod.height_mm({2, 0}), 6.0);                          // along the axis
  EXPECT_NEAR(rod.height_mm({0, 1}), 6.0 - 2.0 + std::sqrt(3.0), 1e-12);  // across it
  EXPECT_NEAR(rod.height_mm({4, 0}), 6.0 - 2.0 + std::sqrt(3.0), 1e-12);  // round past its end
  EXPECT_EQ(rod.height_mm({0, 2.5}), 0.0);
}

TEST(Indenters, RaisedLettersStandTheirReliefOnTheTable) {
  const TextRelief text("T", 6.0, 0.6, 0.35, 0.1, {0, 0});
  // Across the T's stem below its middle: raised to the relief in a band
  // about the stroke wide, the table beside it.
  double stem_x = 0, top = 0;
  int raised = 0;
  for (double x = -2; x <= 2; x += 0.01) {
    const double h = text.height_mm({x, -1.0});
    if (h > top) top = h, stem_x = x;
    raised += h > 0.175;
  }
  EXPECT_NEAR(top, 0.35, 0.01);
  EXPECT_NEAR(raised * 0.01, 0.6, 0.1);
  EXPECT_LT(text.height_mm({stem_x + 1.0, -1.0}), 0.01);
  // Up the stem, raised over most of the letter's 6 mm.
  int along = 0;
  for (double y = -4; y <= 4; y += 0.01) along += text.height_mm({stem_x, y}) > 0.175;
  EXPECT_GT(along * 0.01, 5.0);
  EXPECT_LT(along * 0.01, 7.0);
  EXPECT_EQ(text.height_mm({10, 10}), 0.0);
  EXPECT_NEAR(text.max_height_mm({0, 0}, 1), 0.35, 0.02);
}

TEST(Indenters, APressGoesTheTravelAskedForAndNoFurtherThanAFrame) {
  test::TempDir dir;
  GelSightSimulation sim(
      test::gelsight_scene(dir, test::kPlaneObject, "[contact, render]", "", "s.yaml"), 1,
      std::make_shared<BallIndenter>(4.0, Eigen::Vector2d::Zero(), 8.0));
  const auto press = press_and_render(sim, {0, 0}, 0.3);
  double deepest = 0;
  cv::minMaxLoc(press.truth.height_mm, nullptr, &deepest);
  EXPECT_GE(deepest, 0.3);
  // The first contact frame up to a step (2 mm/s at 25 fps) deep, the last step up to one past.
  EXPECT_LT(deepest, 0.3 + 2 * 0.08 + 1e-6);
}
