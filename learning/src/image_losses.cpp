#include "touchcloud/learning/image_losses.hpp"

namespace touchcloud::learning {

namespace F = torch::nn::functional;

torch::Tensor sample_along_x(const torch::Tensor& image, const torch::Tensor& shift) {
  const std::int64_t w = image.size(3);
  const auto opts = image.options();
  const torch::Tensor columns = torch::arange(w, opts).view({1, 1, 1, w});
  const torch::Tensor x = (columns + shift).clamp(0, static_cast<double>(w - 1));
  const torch::Tensor x0 = x.floor().detach();
  const torch::Tensor weight = x - x0;  // in [0, 1): carries the gradient to the shift
  const torch::Tensor i0 = x0.to(torch::kLong);
  const torch::Tensor i1 = (i0 + 1).clamp_max(w - 1);
  const std::vector<std::int64_t> size = image.sizes().vec();
  const torch::Tensor v0 = image.gather(3, i0.expand(size));
  const torch::Tensor v1 = image.gather(3, i1.expand(size));
  return v0 + weight * (v1 - v0);
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

torch::Tensor appearance_loss(const torch::Tensor& image, const torch::Tensor& reconstructed, double alpha) {
  const torch::Tensor dssim = ((1 - ssim(image, reconstructed)) / 2).clamp(0, 1);
  return (alpha * dssim + (1 - alpha) * (image - reconstructed).abs()).mean();
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

torch::Tensor lr_consistency_loss(const torch::Tensor& dl, const torch::Tensor& dr) {
  const torch::Tensor w = column_weights(dl.size(3), dl.options());
  const torch::Tensor left = (dl - sample_along_x(dr, -dl)).abs();
  const torch::Tensor right = (dr - sample_along_x(dl, dr)).abs();
  return (w * (left + right)).mean();
}

torch::Tensor semantic_loss(const torch::Tensor& d, const torch::Tensor& contact, double rest) {
  const torch::Tensor outside = 1 - contact;
  const torch::Tensor m = outside.sum();
  return ((d - rest).abs() * outside).sum() / m.clamp_min(1);
}

}  // namespace touchcloud::learning
