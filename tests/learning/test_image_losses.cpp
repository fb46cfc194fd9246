// The loss module's terms on tiny hand-checkable tensors (the GS-DepthNet paper, Eq. 2-6).
#include <gtest/gtest.h>

#include "touchcloud/learning/image_losses.hpp"

using namespace touchcloud::learning;

namespace {
torch::Tensor seeded_image(std::int64_t c, std::int64_t h, std::int64_t w) {
  torch::manual_seed(7);
  return torch::rand({1, c, h, w});
}
}  // namespace

TEST(ImageLosses, SsimOfIdenticalImagesIsOne) {
  const torch::Tensor image = seeded_image(3, 8, 10);
  const torch::Tensor s = ssim(image, image);
  EXPECT_EQ(s.sizes(), image.sizes());
  EXPECT_NEAR(s.min().item<double>(), 1.0, 1e-6);
  EXPECT_NEAR(s.max().item<double>(), 1.0, 1e-6);
  EXPECT_NEAR(appearance_loss(image, image, 0.85).item<double>(), 0.0, 1e-7);
  // And below 1 for different images: the measure is not constant.
  EXPECT_LT(ssim(image, seeded_image(3, 8, 10).flip({3})).mean().item<double>(), 0.9);
}

TEST(ImageLosses, SamplerShiftsAnImageByAnIntegerDisparityExactly) {
  const torch::Tensor image = seeded_image(3, 4, 12);
  const torch::Tensor shifted = sample_along_x(image, torch::full({1, 1, 4, 12}, 3.0));
  using torch::indexing::Slice;
  // out(x) = image(x + 3) where x + 3 is inside, the last column beyond; to
  // float rounding of the sampler's normalised coordinates (values in [0, 1]).
  auto max_difference = [](const torch::Tensor& a, const torch::Tensor& b) { return (a - b).abs().max().item<double>(); };
  EXPECT_LT(max_difference(shifted.index({Slice(), Slice(), Slice(), Slice(0, 9)}),
                           image.index({Slice(), Slice(), Slice(), Slice(3, 12)})), 1e-5);
  EXPECT_LT(max_difference(shifted.index({Slice(), Slice(), Slice(), Slice(9, 12)}),
                           image.index({Slice(), Slice(), Slice(), Slice(11, 12)}).expand({1, 3, 4, 3})), 1e-5);
  // Each row reads its own row; a shift of one batch entry serves a batch of images.
  const torch::Tensor two = torch::cat({image, image.flip({2})}, 0);
  const torch::Tensor both = sample_along_x(two, torch::full({1, 1, 4, 12}, 3.0));
  EXPECT_LT(max_difference(both[1].flip({1}), shifted[0]), 1e-5);
  // A half-pixel shift is the mean of the two neighbours, and the shift gets a gradient.
  torch::Tensor half = torch::full({1, 1, 4, 12}, 0.5, torch::requires_grad());
  const torch::Tensor out = sample_along_x(image, half);
  EXPECT_NEAR(out[0][1][2][4].item<double>(), (image[0][1][2][4].item<double>() + image[0][1][2][5].item<double>()) / 2, 1e-6);
  out.sum().backward();
  EXPECT_GT(half.grad().abs().sum().item<double>(), 0);
}

TEST(ImageLosses, LrConsistencyIsZeroForConsistentDisparities) {
  // A constant disparity is consistent with itself in both views, row by
  // row (rows are independent: 1 px in one, 3 px in the other).
  const torch::Tensor dl = torch::full({1, 1, 3, 16}, 2.0), dr = torch::full({1, 1, 3, 16}, 2.0);
  EXPECT_EQ(lr_consistency_loss(dl, dr).item<double>(), 0.0);
  torch::Tensor rows = torch::full({1, 1, 2, 16}, 1.0);
  rows[0][0][1] = 3.0;
  EXPECT_EQ(lr_consistency_loss(rows, rows.clone()).item<double>(), 0.0);
  // Inconsistent: positive.
  EXPECT_GT(lr_consistency_loss(dl, torch::full({1, 1, 3, 16}, 3.0)).item<double>(), 0.0);
}

TEST(ImageLosses, LrConsistencyWeightIsThePapersLinearColumnWeight) {
  const std::int64_t w = 8;
  const torch::Tensor weights = column_weights(w);
  // Eq. 5: w_i = 2 / W (W / 2 - |i - W / 2|): 0 at i = 0, 1 at the centre, 0.25 at i = 7.
  for (std::int64_t i = 0; i < w; ++i)
    EXPECT_DOUBLE_EQ(weights[0][0][0][i].item<double>(), 2.0 / w * (w / 2.0 - std::abs(i - w / 2.0))) << i;
  EXPECT_EQ(weights[0][0][0][0].item<double>(), 0.0);
  EXPECT_EQ(weights[0][0][0][4].item<double>(), 1.0);
  // A left disparity off by 1 px in one column i (d = 0 elsewhere) adds w_i * 1 / N
  // from the left term, and w_j / N from the right term at the column j that reads it.
  for (std::int64_t i : {1, 4, 6}) {
    torch::Tensor dl = torch::zeros({1, 1, 1, w});
    dl[0][0][0][i] = 1.0;  // left x = i reads right x = i - 1 (d_r = 0 there): |1 - 0|
    const torch::Tensor dr = torch::zeros({1, 1, 1, w});
    // The right term at column i: d_r(i) = 0 vs d_l(i + 0) = 1: |0 - 1|, also weight w_i.
    const double expected = 2.0 * weights[0][0][0][i].item<double>() / w;
    EXPECT_NEAR(lr_consistency_loss(dl, dr).item<double>(), expected, 1e-7) << "column " << i;
  }
}

TEST(ImageLosses, SemanticLossIgnoresTheContactRegion) {
  torch::Tensor contact = torch::zeros({1, 1, 4, 4});
  contact.index_put_({0, 0, torch::indexing::Slice(1, 3), torch::indexing::Slice(1, 3)}, 1.0);
  torch::Tensor d = torch::zeros({1, 1, 4, 4});
  // Outside contact at rest (relative disparity 0): 0, whatever the disparity inside.
  d.index_put_({0, 0, torch::indexing::Slice(1, 3), torch::indexing::Slice(1, 3)}, 7.0);
  EXPECT_EQ(semantic_loss(d, contact).item<double>(), 0.0);
  // 2 px off the rest outside contact, either way: mean over the M = 12 pixels outside is 2.
  torch::Tensor raised = d + 2.0;
  raised.index_put_({0, 0, 0, 0}, -2.0);
  raised.index_put_({0, 0, torch::indexing::Slice(1, 3), torch::indexing::Slice(1, 3)}, 30.0);
  EXPECT_DOUBLE_EQ(semantic_loss(raised, contact).item<double>(), 2.0);
  // All in contact: M = 0, the term is 0 (not NaN).
  EXPECT_EQ(semantic_loss(raised, torch::ones({1, 1, 4, 4})).item<double>(), 0.0);
}
