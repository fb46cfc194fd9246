#include "touchcloud/learning/image_losses.hpp"

namespace touchcloud::learning {

namespace F = torch::nn::functional;

torch::Tensor sample_along_x(const torch::Tensor& image, const torch::Tensor& shift) {
  // grid_sample (bilinear, border padding: the edge column beyond the image)
  // rather than two gathers: its forward and backward passes are several
  // times faster on the CPU. Coordinates are normalised to [-1, 1] with
  // align_corners, so an integer shift reads pixel centres up to float rounding.
  const std::int64_t b = image.size(0), h = image.size(2), w = image.size(3);
  const auto opts = image.options();
  const torch::Tensor columns = torch::arange(w, opts).view({1, 1, w});
  const torch::Tensor x = (columns + shift.expand({b, 1, h, w}).squeeze(1)) * (w > 1 ? 2.0 / static_cast<double>(w - 1) : 0.0) - 1;
  const torch::Tensor y = h > 1 ? torch::linspace(-1, 1, h, opts).view({1, h, 1}).expand({b, h, w})
                                : torch::zeros({b, h, w}, opts);
  return F::grid_sample(image, torch::stack({x, y}, 3),
                        F::GridSampleFuncOptions().mode(torch::kBilinear).padding_mode(torch::kBorder).align_corners(true));
}

torch::Tensor ssim(const torch::Tensor& x, const torch::Tensor& y) {
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  auto pool = [](const torch::Tensor& t) {
    return F::avg_pool2d(F::pad(t, F::PadFuncOptions({1, 1, 1, 1}).mode(torch::kReflect)), F::AvgPool2dFuncOptions(3).stride(1));
  };
  const torch::Tensor mx = pool(x), my = pool(y);
  const torch::Tensor sx = pool(x * x) - mx * mx, sy = pool(y * y) - my * my, sxy = pool(x * y) - mx * my;
  return ((2 * mx * my + c1) * (2 * sxy + c2)) / ((mx * mx + my * my + c1) * (sx + sy + c2));
}

namespace {
// Mean of `t` [B, C, H, W] over the pixels where `mask` is 1 (all when undefined).
torch::Tensor masked_mean(const torch::Tensor& t, const torch::Tensor& mask) {
  if (!mask.defined()) return t.mean();
  const torch::Tensor m = mask.expand({t.size(0), 1, t.size(2), t.size(3)});
  return (t * m).sum() / (m.sum() * static_cast<double>(t.size(1))).clamp_min(1);
}
}  // namespace

torch::Tensor appearance_loss(const torch::Tensor& image, const torch::Tensor& reconstructed, double alpha,
                              const torch::Tensor& gel) {
  const torch::Tensor dssim = ((1 - ssim(image, reconstructed)) / 2).clamp(0, 1);
  return masked_mean(alpha * dssim + (1 - alpha) * (image - reconstructed).abs(), gel);
}

torch::Tensor smoothness_loss(const torch::Tensor& d, const torch::Tensor& image) {
  using torch::indexing::Slice;
  const torch::Tensor ddx = (d.index({Slice(), Slice(), Slice(), Slice(1, torch::indexing::None)}) -
                             d.index({Slice(), Slice(), Slice(), Slice(torch::indexing::None, -1)})).abs();
  const torch::Tensor ddy = (d.index({Slice(), Slice(), Slice(1, torch::indexing::None), Slice()}) -
                             d.index({Slice(), Slice(), Slice(torch::indexing::None, -1), Slice()})).abs();
  const torch::Tensor idx = (image.index({Slice(), Slice(), Slice(), Slice(1, torch::indexing::None)}) -
                             image.index({Slice(), Slice(), Slice(), Slice(torch::indexing::None, -1)})).abs().mean(1, true);
  const torch::Tensor idy = (image.index({Slice(), Slice(), Slice(1, torch::indexing::None), Slice()}) -
                             image.index({Slice(), Slice(), Slice(torch::indexing::None, -1), Slice()})).abs().mean(1, true);
  return (ddx * torch::exp(-idx)).mean() + (ddy * torch::exp(-idy)).mean();
}

torch::Tensor column_weights(std::int64_t width, const torch::TensorOptions& options) {
  const torch::Tensor i = torch::arange(width, options.dtype(torch::kFloat32));
  const double half = static_cast<double>(width) / 2;
  return (2.0 / static_cast<double>(width) * (half - (i - half).abs())).view({1, 1, 1, width});
}

torch::Tensor lr_consistency_loss(const torch::Tensor& dl, const torch::Tensor& dr, const torch::Tensor& gel_left,
                                  const torch::Tensor& gel_right) {
  const torch::Tensor w = column_weights(dl.size(3), dl.options());
  const torch::Tensor left = (dl - sample_along_x(dr, -dl)).abs();
  const torch::Tensor right = (dr - sample_along_x(dl, dr)).abs();
  if (!gel_left.defined() && !gel_right.defined()) return (w * (left + right)).mean();
  return masked_mean(w * left, gel_left) + masked_mean(w * right, gel_right);
}

torch::Tensor semantic_loss(const torch::Tensor& relative, const torch::Tensor& contact) {
  const torch::Tensor outside = 1 - contact;
  const torch::Tensor m = outside.sum();
  return (relative.abs() * outside).sum() / m.clamp_min(1);
}

}  // namespace touchcloud::learning
