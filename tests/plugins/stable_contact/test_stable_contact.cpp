// stable_contact follows Eq. 2-3 of the paper: d_i = max_j |Ti[j] - T0[j]|,
// n_i = n_{i-1} + 1 while d_i > l (else 0), stable when n_i > s. The stage is
// driven frame by frame with hand-made tactile clouds.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/types/contact_state.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

using namespace touchcloud;

namespace {

class StableContactStage : public ::testing::Test {
 protected:
  void SetUp() override { start({}); }

  void start(const std::map<std::string, ParamValue>& values) {
    stage_ = registry_.load("stable_contact").create();
    params_ = std::make_unique<ParameterSet>();
    ports_ = std::make_unique<PortSet>();
    stage_->declare(*params_, *ports_);
    for (const auto& [name, value] : values) params_->assign(name, value);
    record_ = RunRecord{};
    ctx_ = std::make_unique<RunContext>("contact", 0, record_);
    stage_->configure(*ctx_);
  }

  // A frame whose largest marker displacement is `d_mm`: three markers, the
  // first at rest, the second moved by d (along z: exact in float, so d = l
  // is tested exactly), the third by d / 2 along a diagonal.
  ContactState frame(double d_mm, std::size_t reference_points = 3) {
    auto reference = std::make_shared<PointCloud>();
    auto points = std::make_shared<PointCloud>();
    const float half_step = static_cast<float>(d_mm / 2 / std::sqrt(3.0));
    for (std::size_t j = 0; j < reference_points; ++j) reference->push_back(pcl::PointXYZ(float(j), 0, 30));
    points->push_back(pcl::PointXYZ(0, 0, 30));
    points->push_back(pcl::PointXYZ(1, 0, 30 - static_cast<float>(d_mm)));
    points->push_back(pcl::PointXYZ(2 + half_step, half_step, 30 - half_step));
    auto tactile = std::make_shared<TactileCloud>();
    tactile->points = points;
    tactile->reference = reference;
    StageIO io(*ports_, {{"tactile", std::any(TactileCloudPtr(tactile))}}, {"state"});
    stage_->process(io, *ctx_);
    return std::any_cast<ContactState>(io.outputs().at("state"));
  }

  PluginRegistry registry_ = touchcloud::test::test_registry();
  std::unique_ptr<Stage> stage_;
  std::unique_ptr<ParameterSet> params_;
  std::unique_ptr<PortSet> ports_;
  RunRecord record_;
  std::unique_ptr<RunContext> ctx_;
};

}  // namespace

TEST_F(StableContactStage, CountsFramesAboveTheThresholdAndResetsBelowIt) {
  start({{"threshold_mm", 2.0}, {"frames", std::int64_t{2}}});
  // d:        0   2.5 2.5 1.0 3   3   3   3   2.0 (not > l)
  // counter:  0   1   2   0   1   2   3   4   0
  // stable:   -   -   -   -   -   -   yes yes -
  const std::vector<double> d = {0, 2.5, 2.5, 1.0, 3, 3, 3, 3, 2.0};
  const std::vector<int> counter = {0, 1, 2, 0, 1, 2, 3, 4, 0};
  for (std::size_t i = 0; i < d.size(); ++i) {
    const ContactState s = frame(d[i]);
    EXPECT_NEAR(s.max_displacement_mm, d[i], 1e-5) << "frame " << i;
    EXPECT_EQ(s.consecutive_frames, counter[i]) << "frame " << i;
    EXPECT_EQ(s.stable, counter[i] > 2) << "frame " << i;
  }
  // Stable first at frame 6: seven frames from the start.
  EXPECT_EQ(record_.metrics.at("contact.frames_to_stable").values, std::vector<double>{7});
}

TEST_F(StableContactStage, ThePapersDefaultsNeedElevenFramesAboveTwoMillimetres) {
  EXPECT_EQ(std::get<double>(*params_->find("threshold_mm")->default_value), 2.0);
  EXPECT_EQ(std::get<std::int64_t>(*params_->find("frames")->default_value), 10);
  for (int i = 1; i <= 10; ++i) EXPECT_FALSE(frame(2.1).stable) << "frame " << i;
  EXPECT_TRUE(frame(2.1).stable);
  EXPECT_TRUE(frame(2.1).stable);
  EXPECT_FALSE(frame(0.0).stable);
  // The next settling counts its frames from the last stable one.
  for (int i = 1; i <= 10; ++i) frame(5.0);
  EXPECT_TRUE(frame(5.0).stable);
  EXPECT_EQ(record_.metrics.at("contact.frames_to_stable").values, (std::vector<double>{11, 12}));
}

TEST_F(StableContactStage, RefusesCloudsThatCannotBePairedWithTheirReference) {
  EXPECT_THROW(frame(1.0, 4), RunError);
}
