// Differentiable image terms of self-supervised stereo (the GS-DepthNet paper, Section
// III-C/D), on float tensors [B, C, H, W]. Disparities are in pixels of the
// image they are applied to, [B, 1, H, W]. Includes torch: network code only.
#pragma once

#include <torch/torch.h>

namespace touchcloud::learning {

// Bilinear sampler along the rows: out(x, y) = image(x + shift(x, y), y),
// linear between the two neighbouring columns, clamped at the borders;
// differentiable in the image and in the shift. An integer shift moves the
// image by that many columns, exactly up to float rounding (1e-5 of a value).
// `shift` is [B or 1, 1, H, W] for an image of [B, C, H, W].
torch::Tensor sample_along_x(const torch::Tensor& image, const torch::Tensor& shift);

// Single-scale SSIM map (3 x 3 mean windows, reflection padding; C1 = 0.01^2,
// C2 = 0.03^2 for images in [0, 1]), the size of the inputs.
torch::Tensor ssim(const torch::Tensor& x, const torch::Tensor& y);

// Eq. 2: mean of alpha (1 - SSIM) / 2 + (1 - alpha) |I - I~|.
// `gel` (optional, [1 or B, 1, H, W], 1 where the view sees the gel): the
// mean over those pixels only (the housing around the gel has nothing to match).
torch::Tensor appearance_loss(const torch::Tensor& image, const torch::Tensor& reconstructed, double alpha,
                              const torch::Tensor& gel = {});

// Eq. 3: mean of |dx d| exp(-|dx I|) + |dy d| exp(-|dy I|) (the image's
// gradient averaged over its channels); `image` at the disparity's size.
torch::Tensor smoothness_loss(const torch::Tensor& disparity, const torch::Tensor& image);

// Eq. 5: w_i = 2 / W (W / 2 - |i - W / 2|) of every column i, [1, 1, 1, W].
torch::Tensor column_weights(std::int64_t width, const torch::TensorOptions& options = {});

// Eq. 4-5 in this toolkit's sign convention (dense_maps.hpp: both
// disparities >= 0; left x matches right x - d_l, right x matches left
// x + d_r): mean of w_i (|d_l(x) - d_r(x - d_l(x))| + |d_r(x) - d_l(x + d_r(x))|).
// `gel_left`, `gel_right` (optional): each view's term averaged over its gel pixels only.
torch::Tensor lr_consistency_loss(const torch::Tensor& disparity_left, const torch::Tensor& disparity_right,
                                  const torch::Tensor& gel_left = {}, const torch::Tensor& gel_right = {});

// Eq. 6: sum of |relative| over the pixels outside contact, divided by their
// number M (0 when every pixel is in contact). `contact` is 1 in contact, 0
// elsewhere, [B, 1, H, W]. `relative`: the disparity relative to the gel at
// rest, the paper's disparity (0 outside contact).
torch::Tensor semantic_loss(const torch::Tensor& relative, const torch::Tensor& contact);

}  // namespace touchcloud::learning
