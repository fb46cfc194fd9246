// A camera's sequence numbers: every step past one is a frame lost,
// including frames lost from the queue before the first one was taken
// (behind a slow stage a full queue drops its oldest before anything reads
// it); without the first sequence delivered, nothing before the first seen
// is claimed.
#include <gtest/gtest.h>

#include "touchcloud/plugin_kit/camera/frame_tally.hpp"

using touchcloud::camera::SequenceGaps;

TEST(SequenceGaps, StepsPastOneAreFramesLost) {
  SequenceGaps gaps;
  for (std::int64_t s : {0, 1, 4, 5, 9}) gaps.see(s);
  EXPECT_EQ(gaps.dropped(), 5);
}

TEST(SequenceGaps, FramesLostBeforeTheFirstTakenCountFromTheFirstDelivered) {
  SequenceGaps gaps;
  gaps.see(2, 0);  // frames 0 and 1 dropped from the queue before the first read
  gaps.see(3, 0);
  EXPECT_EQ(gaps.dropped(), 2);
  SequenceGaps unknown;
  unknown.see(2);
  EXPECT_EQ(unknown.dropped(), 0);
}
