// GS-DepthNet's layer table against the network, a few training steps on a
// tiny seeded dataset, the checkpoint round trip, the training loop's
// schedule and batches, and the checkpoint file's refusals.
#include <gtest/gtest.h>

#include <iostream>

#include "test_support.hpp"
#include "tiny_stereo_dataset.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/gs_depthnet.hpp"
#include "touchcloud/learning/stereo_samples.hpp"
#include "touchcloud/learning/torch_io.hpp"
#include "touchcloud/learning/training_loop.hpp"

using namespace touchcloud;
using namespace touchcloud::learning;
using namespace touchcloud::test;

namespace {
GsDepthNetShape tiny_shape(int width = 2) {
  GsDepthNetShape s;
  s.width = width;
  s.input_width_px = s.input_height_px = 64;
  s.d_max_px = 4;
  s.min_disparity_px = -1;
  return s;
}
// The tiny dataset's gel at rest: 3 px everywhere, in both views (or as a
// matcher might have measured it, `px`).
ReferenceDisparity tiny_reference(float px = 3) {
  ReferenceDisparity r;
  r.left_px = r.right_px = cv::Mat(64, 64, CV_32FC1, cv::Scalar(px));
  r.gel_left = r.gel_right = cv::Mat(64, 64, CV_8UC1, cv::Scalar(255));
  return r;
}
}  // namespace

TEST(GsDepthNet, LayerTableGivesTheNetworksParametersAndOutputSizes) {
  for (int width : {2, 8}) {
    const GsDepthNetShape shape = tiny_shape(width);
    GsDepthNet net(shape, tiny_reference());
    std::int64_t counted = 0;
    for (const auto& p : net->parameters()) counted += p.numel();
    EXPECT_EQ(counted, gs_depthnet_parameters(shape)) << "width " << width;
    torch::NoGradGuard no_grad;
    const auto scales = net->forward(torch::rand({1, 3, 64, 64}), torch::rand({1, 3, 64, 64}));
    ASSERT_EQ(scales.size(), 4u);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(scales[k].left.size(3), 64 >> (3 - k));  // 8, 16, 32, 64: each double the previous
      EXPECT_EQ(scales[k].right.sizes(), scales[k].left.sizes());
      // Bounded: the rest disparity + offset + d_max * sigmoid, in both views.
      for (const auto* d : {&scales[k].left, &scales[k].right}) {
        EXPECT_GE(d->min().item<double>(), 2.0);
        EXPECT_LE(d->max().item<double>(), 6.0);
      }
      EXPECT_TRUE(torch::allclose(scales[k].left - 3, scales[k].left_relative, 0, 1e-5));
    }
  }
  // FLOPs by hand for width 1 at 32 x 32: each layer 2 * 9 * cin * cout * h * w.
  GsDepthNetShape one = tiny_shape(1);
  one.input_width_px = one.input_height_px = 32;
  double expected = 0;
  for (const auto& l : gs_depthnet_layers(one)) expected += 2.0 * 9 * l.in_channels * l.out_channels * l.out_height * l.out_width;
  EXPECT_EQ(gs_depthnet_flops(one), 2 * expected);  // a pass per view
  // The first layer takes the pair's 6 channels and one matching cost per
  // whole-pixel shift of -1 + [0, 4] px (-1, 0, 1, 2, 3): 11 -> 1 channels at 16 x 16.
  EXPECT_EQ(one.cost_shifts(), (std::vector<int>{-1, 0, 1, 2, 3}));
  EXPECT_EQ(gs_depthnet_layers(one).front().in_channels, 11);
  EXPECT_EQ(gs_depthnet_layers(one).front().out_height, 16);
}

// The matching costs: where the other view shows the view's content s
// columns to the left, the cost at shift s is 0 and the others are not.
TEST(GsDepthNet, MatchingCostsVanishAtTheShiftThatAlignsTheViews) {
  torch::manual_seed(5);
  const torch::Tensor texture = torch::rand({1, 3, 8, 40});
  using torch::indexing::Slice;
  const torch::Tensor view = texture.index({Slice(), Slice(), Slice(), Slice(4, 36)});
  const torch::Tensor other = texture.index({Slice(), Slice(), Slice(), Slice(6, 38)});  // other(x - 2) = view(x)
  const torch::Tensor costs = matching_costs(view, other, {-1, 0, 1, 2, 3});
  ASSERT_EQ(costs.sizes(), (std::vector<std::int64_t>{1, 5, 8, 32}));
  const auto inner = [&](int k) { return costs.index({0, k, Slice(), Slice(4, 28)}); };
  EXPECT_LT(inner(3).abs().max().item<double>(), 1e-6);  // shift 2
  for (int k : {0, 1, 2, 4}) EXPECT_GT(inner(k).min().item<double>(), 0.05) << "shift " << k - 1;
  // Each cost is the 3 x 3 box average (edges replicated) of the per-pixel
  // mean absolute colour difference, as libtorch's avg_pool2d gives it.
  namespace F = torch::nn::functional;
  const torch::Tensor padded = F::pad(other, F::PadFuncOptions({3, 3, 0, 0}).mode(torch::kReplicate));
  const torch::Tensor raw = (view - padded.narrow(3, 3 - 2, 32)).abs().mean(1, true);
  const torch::Tensor box = F::avg_pool2d(F::pad(raw, F::PadFuncOptions({1, 1, 1, 1}).mode(torch::kReplicate)),
                                          F::AvgPool2dFuncOptions(3).stride(1));
  EXPECT_LT((costs.narrow(1, 3, 1) - box).abs().max().item<double>(), 1e-6);
}

// The rest disparity is measured 1 px short (2 px for the true 3): the
// untrained network is 1 px off everywhere, and a few steps of the
// self-supervised losses alone bring it toward the truth.
TEST(GsDepthNet, AFewTrainingStepsOnATinySeededDatasetReduceTheLoss) {
  TempDir dir;
  const StereoSamples set = read_stereo_samples(tiny::write(dir.path() / "data", 4, 64));
  std::vector<cv::Mat> lefts, rights, masks, truths;
  for (const auto& s : set.samples)
    lefts.push_back(s.left), rights.push_back(s.right), masks.push_back(s.contact_mask),
        truths.push_back(s.disparity_left_px);
  const torch::Tensor l = image_batch(lefts), r = image_batch(rights), m = image_batch(masks).gt(0.5).to(torch::kFloat32);
  const torch::Tensor truth = image_batch(truths);
  torch::manual_seed(1);
  const GsDepthNetShape shape = tiny_shape(4);
  GsDepthNet net(shape, tiny_reference(2));
  torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(1e-3));
  const LossWeights weights;
  auto error_px = [&] {  // mean |left disparity - truth| away from the image's sides
    torch::NoGradGuard no_grad;
    using torch::indexing::Slice;
    const torch::Tensor d = net->forward(l, r).back().left;
    return (d - truth).abs().index({Slice(), Slice(), Slice(), Slice(8, 56)}).mean().item<double>();
  };
  const double error_before = error_px();
  double first = 0, last = 0;
  for (int step = 0; step < 30; ++step) {
    adam.zero_grad();
    const auto terms = gs_depthnet_loss(net->forward(l, r), l, r, m, weights);
    terms.total.backward();
    adam.step();
    (step == 0 ? first : last) = terms.total.item<double>();
    ASSERT_TRUE(std::isfinite(terms.total.item<double>()));
  }
  const double error_after = error_px();
  std::cout << "loss " << first << " -> " << last << ", error " << error_before << " -> " << error_after << " px\n";
  EXPECT_LT(last, 0.8 * first) << "first " << first << ", last " << last;
  EXPECT_LT(error_after, 0.6 * error_before) << "error " << error_before << " -> " << error_after << " px";
}

TEST(GsDepthNet, CheckpointRoundTripGivesTheSameDisparitiesBitForBit) {
  TempDir dir;
  torch::manual_seed(3);
  const GsDepthNetShape shape = tiny_shape(3);
  GsDepthNet net(shape, tiny_reference());
  Checkpoint c;
  c.header = shape.header();
  c.header.training_fields = {{"epochs_done", "0"}};
  c.blobs = {{"weights", module_bytes(*net)}};
  write_file(dir.path() / "net.ckpt", checkpoint_bytes(c));

  const Checkpoint back = read_checkpoint(dir.path() / "net.ckpt");
  EXPECT_EQ(back.header.describe(), c.header.describe());
  const GsDepthNetShape shape_back = GsDepthNetShape::from_header(back.header, "net.ckpt");
  torch::manual_seed(99);  // other initial weights: the loaded ones must replace them
  GsDepthNet loaded(shape_back, tiny_reference());
  load_module_bytes(*loaded, back.blob("weights", "net.ckpt"), "net.ckpt");
  net->eval();
  loaded->eval();
  torch::NoGradGuard no_grad;
  const torch::Tensor a = torch::rand({2, 3, 64, 64}), b = torch::rand({2, 3, 64, 64});
  const auto x = net->forward(a, b), y = loaded->forward(a, b);
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_TRUE(torch::equal(x[k].left, y[k].left)) << k;
    EXPECT_TRUE(torch::equal(x[k].right, y[k].right)) << k;
  }
}

TEST(Checkpoint, RefusesMissingCorruptAndOtherNetworksNamingTheFile) {
  TempDir dir;
  const auto missing = (dir.path() / "none.ckpt").string();
  EXPECT_NE(input_error_of([&] { read_checkpoint(missing); }).find(missing), std::string::npos);
  write_file(dir.path() / "junk.ckpt", "PK\x03\x04 not a checkpoint");
  const std::string junk = input_error_of([&] { read_checkpoint(dir.path() / "junk.ckpt"); });
  EXPECT_NE(junk.find("junk.ckpt"), std::string::npos) << junk;
  EXPECT_NE(junk.find("not a touchcloud checkpoint"), std::string::npos) << junk;

  // Truncated weights.
  Checkpoint c;
  c.header = tiny_shape().header();
  GsDepthNet net(tiny_shape(), tiny_reference());
  c.blobs = {{"weights", module_bytes(*net)}};
  const std::string bytes = checkpoint_bytes(c);
  write_file(dir.path() / "cut.ckpt", bytes.substr(0, bytes.size() / 2));
  const std::string cut = input_error_of([&] { read_checkpoint(dir.path() / "cut.ckpt"); });
  EXPECT_NE(cut.find("cut.ckpt"), std::string::npos) << cut;
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;
  // Weights that are not a torch archive.
  Checkpoint garbled = c;
  garbled.blobs = {{"weights", std::string(1000, 'x')}};
  write_file(dir.path() / "garbled.ckpt", checkpoint_bytes(garbled));
  const Checkpoint g = read_checkpoint(dir.path() / "garbled.ckpt");
  const std::string load = input_error_of([&] { load_module_bytes(*net, g.blob("weights", "garbled.ckpt"), "garbled.ckpt"); });
  EXPECT_NE(load.find("garbled.ckpt: the weights do not load"), std::string::npos) << load;

  // Another width, another input size, another architecture: both named.
  const std::string width = input_error_of([&] { require_same_network(tiny_shape(4).header(), tiny_shape(2).header(), "w.ckpt"); });
  EXPECT_NE(width.find("w.ckpt"), std::string::npos);
  EXPECT_NE(width.find("width 4"), std::string::npos) << width;
  EXPECT_NE(width.find("width 2"), std::string::npos) << width;
  GsDepthNetShape big = tiny_shape();
  big.input_width_px = 128;
  const std::string size = input_error_of([&] { require_same_network(big.header(), tiny_shape().header(), "s.ckpt"); });
  EXPECT_NE(size.find("128 x 64 x 6"), std::string::npos) << size;
  EXPECT_NE(size.find("64 x 64 x 6"), std::string::npos) << size;
  CheckpointHeader other = tiny_shape().header();
  other.architecture = "gelsight_unet";
  const std::string arch = input_error_of([&] { GsDepthNetShape::from_header(other, "o.ckpt"); });
  EXPECT_NE(arch.find("o.ckpt"), std::string::npos) << arch;
  EXPECT_NE(arch.find("gelsight_unet"), std::string::npos) << arch;
  EXPECT_NE(arch.find("gs_depthnet"), std::string::npos) << arch;
}

// A blob larger than the file is bad input before anything is allocated
// (not std::bad_alloc), naming the file and the blob.
TEST(Checkpoint, ABlobLargerThanTheFileIsRefusedBeforeAllocating) {
  TempDir dir;
  const std::string header = "touchcloud checkpoint 1\narchitecture gs_depthnet\ninput 64 64 6\n";
  for (const std::string size : {"9000000000000000000", "1000"}) {
    write_file(dir.path() / "huge.ckpt", header + "blob weights " + size + "\n" + std::string(10, 'x') + "\n");
    const std::string e = input_error_of([&] { read_checkpoint(dir.path() / "huge.ckpt"); });
    EXPECT_NE(e.find("huge.ckpt:4: blob 'weights' declares " + size + " bytes, but only 11 follow (corrupt or truncated)"),
              std::string::npos)
        << e;
  }
}

// The header's width builds the network; weights of another width would
// replace its tensors whatever their shape.
TEST(Checkpoint, WeightsThatDisagreeWithTheHeaderAreRefused) {
  GsDepthNet wide(tiny_shape(4), tiny_reference());
  GsDepthNet narrow(tiny_shape(2), tiny_reference());
  const std::string e = input_error_of([&] { load_module_bytes(*narrow, module_bytes(*wide), "w.ckpt"); });
  EXPECT_NE(e.find("w.ckpt: the weights do not fit the network its header describes"), std::string::npos) << e;
  EXPECT_NE(e.find("' is [1, 4, 3, 3], the header's network needs [1, 2, 3, 3]"), std::string::npos) << e;
}

TEST(TrainingLoop, ScheduleHalvesAfterTheConstantEpochsAndBatchesCoverEverySample) {
  LearningRateSchedule s;
  s.initial = 1e-4;
  s.constant_epochs = 30;
  s.halve_every = 10;
  EXPECT_EQ(s.rate(0), 1e-4);
  EXPECT_EQ(s.rate(29), 1e-4);
  EXPECT_EQ(s.rate(30), 0.5e-4);
  EXPECT_EQ(s.rate(39), 0.5e-4);
  EXPECT_EQ(s.rate(40), 0.25e-4);
  std::mt19937_64 a(5), b(5);
  const auto batches = shuffled_batches(10, 4, a);
  ASSERT_EQ(batches.size(), 3u);
  EXPECT_EQ(batches[2].size(), 2u);
  std::vector<std::int64_t> all;
  for (const auto& batch : batches) all.insert(all.end(), batch.begin(), batch.end());
  std::sort(all.begin(), all.end());
  for (std::int64_t i = 0; i < 10; ++i) EXPECT_EQ(all[i], i);
  EXPECT_EQ(shuffled_batches(10, 4, b), batches);  // seeded: the same order
  // An empty dataset folder is refused naming its index.
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "empty");
  write_file(dir.path() / "empty" / "index.csv", "index,timestamp_s,left,right,disparity_left,valid_left,disparity_right,"
                                                  "valid_right,depth_mm,depth_valid,contact_mask\n");
  const std::string empty = input_error_of([&] { read_stereo_samples(dir.path() / "empty" / "index.csv"); });
  EXPECT_NE(empty.find("empty/index.csv lists no pairs"), std::string::npos) << empty;
}
