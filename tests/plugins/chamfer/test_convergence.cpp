// Convergence touches on hand-made score histories.
#include <gtest/gtest.h>

#include "convergence.hpp"

using namespace touchcloud::chamfer;

using touchcloud::chamfer::convergence_touches;

TEST(Convergence, CountsTouchesUntilTheScoreStaysWithinFivePercent) {
  // Final 1.0: 1.04 and 0.96 are within 5 %, 1.2 is not; the last score
  // outside the band is touch 3, so the score has converged after touch 4.
  EXPECT_EQ(convergence_touches({5.0, 2.0, 1.2, 1.04, 0.96, 1.0}), 4);
}

TEST(Convergence, ALateExcursionDelaysConvergence) {
  EXPECT_EQ(convergence_touches({1.0, 1.0, 1.5, 1.0}), 4);
}

TEST(Convergence, FlatHistoryConvergesAtOnceAndEmptyNever) {
  EXPECT_EQ(convergence_touches({2.0, 2.0, 2.0}), 1);
  EXPECT_EQ(convergence_touches({}), 0);
  EXPECT_EQ(convergence_touches({3.0}), 1);
}
