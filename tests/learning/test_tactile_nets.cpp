// ContactNet and TactileDepthNet: the layer tables against the
// networks, output shapes, a few training steps on a tiny seeded set, the
// checkpoint round trip, the augmentation, and the refusals of other
// networks and input sizes.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "tiny_tactile_dataset.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/tactile_net_pair.hpp"
#include "touchcloud/learning/tactile_nets.hpp"
#include "touchcloud/learning/torch_io.hpp"

using namespace touchcloud;
using namespace touchcloud::learning;
using namespace touchcloud::test;

namespace {

TactileNetShape tiny_shape(TactileNet net, int width = 2) {
  TactileNetShape s;
  s.net = net;
  s.width = width;
  s.input_width_px = tiny_tactile::kWidth;
  s.input_height_px = tiny_tactile::kHeight;
  return s;
}

struct TinySet {
  torch::Tensor difference, height, mask;
};

TinySet tiny_set(int count) {
  std::vector<cv::Mat> images, heights, masks;
  for (int i = 0; i < count; ++i) {
    const auto s = tiny_tactile::sample(i);
    images.push_back(s.image), heights.push_back(s.height_mm), masks.push_back(s.mask);
  }
  return {tactile_difference_batch(images, tiny_tactile::reference()), image_batch(heights),
          image_batch(masks).gt(0.5).to(torch::kFloat32)};
}

std::int64_t counted_parameters(const torch::nn::Module& net) {
  std::int64_t n = 0;
  for (const auto& p : net.parameters()) n += p.numel();
  return n;
}

}  // namespace

TEST(TactileNets, LayerTablesGiveTheNetworksParametersAndTheOutputsHaveTheInputSize) {
  for (int width : {2, 8}) {
    ContactNet contact(tiny_shape(TactileNet::Contact, width));
    TactileDepthNet depth(tiny_shape(TactileNet::Depth, width));
    EXPECT_EQ(counted_parameters(*contact), tactile_net_parameters(tiny_shape(TactileNet::Contact, width))) << width;
    EXPECT_EQ(counted_parameters(*depth), tactile_net_parameters(tiny_shape(TactileNet::Depth, width))) << width;
    contact->eval();
    torch::NoGradGuard no_grad;
    const torch::Tensor d = torch::rand({2, 3, 48, 64}) - 0.5;
    const torch::Tensor logits = contact->forward(d);
    EXPECT_EQ(logits.sizes(), (std::vector<std::int64_t>{2, 1, 48, 64}));
    const torch::Tensor height = depth->forward(d, torch::sigmoid(logits));
    EXPECT_EQ(height.sizes(), (std::vector<std::int64_t>{2, 1, 48, 64}));
  }
  // By hand, width 1 at 64 x 48: ContactNet's fc1 takes conv5's 1 channel at
  // 4 x 3 and gives 8; its transposed convolution 3 -> 1 channels, kernel 8,
  // over 16 x 12 input pixels.
  const auto layers = tactile_net_layers(tiny_shape(TactileNet::Contact, 1));
  ASSERT_EQ(layers.size(), 8u);  // five convolutions, two fully connected, one transposed
  EXPECT_EQ(layers[5].name, "fc1");
  EXPECT_EQ(layers[5].parameters, 12 * 8 + 8);
  EXPECT_EQ(layers[6].parameters, 8 * 12 + 12);
  EXPECT_EQ(layers[7].parameters, 3 * 64 + 1);
  EXPECT_EQ(layers[7].flops, 2.0 * 3 * 64 * 16 * 12);
  EXPECT_EQ(layers[0].flops, 2.0 * 3 * 9 * 1 * 24 * 32);  // conv1: 3 -> 1 channels, 3 x 3, at 32 x 24
  const auto depth_layers = tactile_net_layers(tiny_shape(TactileNet::Depth, 1));
  ASSERT_EQ(depth_layers.size(), 3u);  // three convolutions
  EXPECT_EQ(depth_layers[0].parameters, 4 * 2 * 25 + 2);  // image and contact probability in
  EXPECT_EQ(depth_layers[2].out_channels, 1);
}

TEST(TactileNets, AFewTrainingStepsOnATinySeededSetReduceEachLoss) {
  const TinySet set = tiny_set(6);
  torch::manual_seed(1);
  ContactNet contact(tiny_shape(TactileNet::Contact, 4));
  const auto [mean, deviation] = channel_statistics(set.difference);
  contact->set_normalisation(mean, deviation);
  contact->set_contact_prior(set.mask.mean().item<double>());
  torch::optim::Adam adam(contact->parameters(), torch::optim::AdamOptions(1e-3));
  double first = 0, last = 0;
  for (int step = 0; step < 40; ++step) {
    adam.zero_grad();
    const torch::Tensor loss = contact_loss(contact->forward(set.difference), set.mask);
    loss.backward();
    adam.step();
    (step == 0 ? first : last) = loss.item<double>();
  }
  EXPECT_LT(last, 0.7 * first) << "ContactNet: first " << first << ", last " << last;

  contact->eval();
  torch::Tensor probability;
  {
    torch::NoGradGuard no_grad;
    probability = torch::sigmoid(contact->forward(set.difference));
  }
  TactileDepthNet depth(tiny_shape(TactileNet::Depth, 4));
  depth->set_normalisation(mean, deviation);
  torch::optim::Adam depth_adam(depth->parameters(), torch::optim::AdamOptions(1e-3));
  for (int step = 0; step < 40; ++step) {
    depth_adam.zero_grad();
    const torch::Tensor loss = depth_loss(depth->forward(set.difference, probability), set.height);
    loss.backward();
    depth_adam.step();
    (step == 0 ? first : last) = loss.item<double>();
  }
  EXPECT_LT(last, 0.7 * first) << "TactileDepthNet: first " << first << ", last " << last;
}

TEST(TactileNets, DepthLossIsTheMeanOfEachImagesFrobeniusNorm) {
  const torch::Tensor truth = torch::zeros({2, 1, 2, 2});
  torch::Tensor height = torch::zeros({2, 1, 2, 2});
  height[0].fill_(1);       // four errors of 1 mm: norm 2
  height[1][0][0][0] = 3;   // one of 3 mm: norm 3
  EXPECT_NEAR(depth_loss(height, truth).item<double>(), 2.5, 1e-6);
}

TEST(TactileNets, CheckpointRoundTripGivesTheSameOutputsBitForBit) {
  TempDir dir;
  const TinySet set = tiny_set(3);
  const auto [mean, deviation] = channel_statistics(set.difference);
  torch::manual_seed(3);
  ContactNet contact(tiny_shape(TactileNet::Contact, 3));
  TactileDepthNet depth(tiny_shape(TactileNet::Depth, 3));
  contact->set_normalisation(mean, deviation);
  depth->set_normalisation(mean, deviation);
  const Fields sensor = {{"sensor", "gelsight_mini"}, {"mm_per_px", "0.06"}, {"gel_thickness_mm", "2.5"}};
  Checkpoint c, d;
  c.header = contact->shape().header();
  c.blobs = {{"weights", module_bytes(*contact)}};
  d.header = depth->shape().header();
  d.header.training_fields = sensor;
  d.blobs = {{"weights", module_bytes(*depth)}};
  write_file(dir.path() / "contact.ckpt", checkpoint_bytes(c));
  write_file(dir.path() / "depth.ckpt", checkpoint_bytes(d));

  torch::manual_seed(99);  // other initial weights: the loaded ones must replace them
  TactileNetPair loaded(dir.path() / "contact.ckpt", dir.path() / "depth.ckpt");
  EXPECT_EQ(loaded.headers().contact.width, 3);
  EXPECT_EQ(loaded.headers().sensor.mm_per_px, 0.06);
  contact->eval();
  depth->eval();
  const auto s = tiny_tactile::sample(4);
  const TactilePrediction p = loaded.predict(s.image, tiny_tactile::reference());
  torch::NoGradGuard no_grad;
  const torch::Tensor diff = tactile_difference_batch({s.image}, tiny_tactile::reference());
  const torch::Tensor probability = torch::sigmoid(contact->forward(diff));
  EXPECT_EQ(cv::norm(p.contact_probability, tensor_image(probability), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(p.height_mm, tensor_image(depth->forward(diff, probability)), cv::NORM_INF), 0.0);
  // The normalisation travels with the weights.
  ContactNet back(tiny_shape(TactileNet::Contact, 3));
  load_module_bytes(*back, read_checkpoint(dir.path() / "contact.ckpt").blob("weights", "contact.ckpt"), "contact.ckpt");
  EXPECT_TRUE(torch::equal(back->named_buffers()["input.deviation"], deviation));
  EXPECT_EQ(module_bytes(*back), module_bytes(*contact));
}

TEST(TactileNets, AugmentationFlipsAndRotatesImageAndTargetsAlikeAndIsSeeded) {
  const TinySet set = tiny_set(4);
  // No rotation, always flipped: the mirror image, to float rounding.
  TactileAugmentation mirror{0, 1};
  torch::Tensor d = set.difference.clone(), h = set.height.clone(), m = set.mask.clone();
  std::mt19937_64 rng(1);
  augment({&d, &h}, {&m}, mirror, rng);
  EXPECT_TRUE(torch::allclose(d, set.difference.flip({3}), 1e-5, 1e-6));
  EXPECT_TRUE(torch::equal(m, set.mask.flip({3})));
  // Rotated within 5 degrees: the mask stays 0/1, the contact keeps about its size.
  TactileAugmentation rotate{5, 0};
  torch::Tensor d1 = set.difference.clone(), m1 = set.mask.clone(), d2 = set.difference.clone(), m2 = set.mask.clone();
  std::mt19937_64 a(7), b(7);
  augment({&d1}, {&m1}, rotate, a);
  augment({&d2}, {&m2}, rotate, b);
  EXPECT_TRUE(torch::equal(d1, d2));  // the same seed, the same angles
  EXPECT_FALSE(torch::equal(d1, set.difference));
  EXPECT_TRUE(torch::equal(m1, m1.gt(0.5).to(torch::kFloat32)));
  EXPECT_NEAR(m1.sum().item<double>(), set.mask.sum().item<double>(), 0.05 * set.mask.sum().item<double>());
}

TEST(TactileNets, OtherArchitecturesAndInputSizesAreRefusedNamingBoth) {
  CheckpointHeader gs = tiny_shape(TactileNet::Contact).header();
  gs.architecture = "gs_depthnet";
  const std::string arch = input_error_of([&] { TactileNetShape::from_header(gs, TactileNet::Contact, "o.ckpt"); });
  EXPECT_NE(arch.find("o.ckpt"), std::string::npos) << arch;
  EXPECT_NE(arch.find("gs_depthnet"), std::string::npos) << arch;
  EXPECT_NE(arch.find("needs a contact_net checkpoint"), std::string::npos) << arch;
  TactileNetShape odd = tiny_shape(TactileNet::Contact);
  odd.input_height_px = 40;
  EXPECT_NE(odd.size_problem().find("multiples of 16"), std::string::npos);
  const std::string size = input_error_of([&] { TactileNetShape::from_header(odd.header(), TactileNet::Contact, "s.ckpt"); });
  EXPECT_NE(size.find("64 x 40"), std::string::npos) << size;

  TempDir dir;
  Checkpoint c, d;
  c.header = tiny_shape(TactileNet::Contact).header();
  TactileNetShape big = tiny_shape(TactileNet::Depth);
  big.input_width_px = 128;
  d.header = big.header();
  d.header.training_fields = {{"mm_per_px", "0.06"}, {"gel_thickness_mm", "2.5"}};
  write_file(dir.path() / "c.ckpt", checkpoint_bytes(c));
  write_file(dir.path() / "d.ckpt", checkpoint_bytes(d));
  const std::string pair = input_error_of([&] { TactileNetHeaders::read(dir.path() / "c.ckpt", dir.path() / "d.ckpt"); });
  EXPECT_NE(pair.find("128 x 48 x 3"), std::string::npos) << pair;
  EXPECT_NE(pair.find("64 x 48 x 3"), std::string::npos) << pair;
  EXPECT_NE(pair.find("must share the input size"), std::string::npos) << pair;
}
