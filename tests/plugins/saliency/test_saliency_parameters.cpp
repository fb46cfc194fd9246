// alpha = 1 would keep nothing on every touch (nothing is above the maximum)
// and the run would blame "no contact": the value itself is refused.
#include <gtest/gtest.h>

#include "stage_harness.hpp"

using namespace touchcloud;

TEST(SaliencyParameters, AlphaOfOneIsRefusedAndJustBelowIsKept) {
  try {
    test::StageHarness stage("saliency", {{"alpha", 1.0}});
    FAIL() << "alpha = 1 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("alpha"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("must be in [0, 1)"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(test::StageHarness("saliency", {{"alpha", 0.99}}));
}
