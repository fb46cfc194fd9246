#include "touchcloud/learning/gs_depthnet.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/error.hpp"
#include "touchcloud/learning/image_losses.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/version.hpp"

namespace touchcloud::learning {

namespace F = torch::nn::functional;

namespace {
constexpr const char* kArchitecture = "gs_depthnet";

double parse_number(const CheckpointHeader& h, const std::string& name, const std::string& file) {
  const std::string& text = h.field(name, file);
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw InputError(file + ": architecture field '" + name + "' is '" + text + "', not a number");
}
}  // namespace

std::vector<int> GsDepthNetShape::cost_shifts() const {
  std::vector<int> shifts;
  for (int s = static_cast<int>(std::ceil(min_disparity_px)); s <= std::floor(min_disparity_px + d_max_px); ++s)
    shifts.push_back(s);
  return shifts;
}

CheckpointHeader GsDepthNetShape::header() const {
  CheckpointHeader h;
  h.architecture = kArchitecture;
  h.toolkit_version = kVersion;
  h.input_width_px = input_width_px;
  h.input_height_px = input_height_px;
  h.input_channels = 6;
  h.architecture_fields = {{"width", std::to_string(width)},
                           {"d_max_px", number_text(d_max_px)},
                           {"min_disparity_px", number_text(min_disparity_px)},
                           {"matching_costs", std::to_string(cost_shifts().size())}};
  return h;
}

GsDepthNetShape GsDepthNetShape::from_header(const CheckpointHeader& h, const std::string& file) {
  if (h.architecture != kArchitecture)
    throw InputError(file + ": the checkpoint is " + h.describe() + "; this stage needs a " + kArchitecture +
                     " checkpoint");
  GsDepthNetShape s;
  s.width = static_cast<int>(parse_number(h, "width", file));
  s.d_max_px = parse_number(h, "d_max_px", file);
  s.min_disparity_px = parse_number(h, "min_disparity_px", file);
  s.input_width_px = h.input_width_px;
  s.input_height_px = h.input_height_px;
  if (s.width < 1 || s.d_max_px <= 0 || h.input_channels != 6 || s.input_width_px % 32 || s.input_height_px % 32 ||
      parse_number(h, "matching_costs", file) != static_cast<double>(s.cost_shifts().size()))
    throw InputError(file + ": the checkpoint's " + h.describe() +
                     " is not a valid GS-DepthNet (width >= 1, d_max_px > 0, 6 channels, sides multiples of 32, one "
                     "matching cost per whole-pixel shift of the output range)");
  return s;
}

std::vector<ConvLayer> gs_depthnet_layers(const GsDepthNetShape& s) {
  const int c = s.width, h = s.input_height_px, w = s.input_width_px;
  auto at = [&](const std::string& name, int in, int out, int down) {
    return ConvLayer{name, in, out, 3, h / down, w / down};
  };
  return {
      at("enc1a", 6 + static_cast<int>(s.cost_shifts().size()), c, 2), at("enc1b", c, c, 2),
      at("enc2a", c, 2 * c, 4),      at("enc2b", 2 * c, 2 * c, 4),
      at("enc3a", 2 * c, 4 * c, 8),  at("enc3b", 4 * c, 4 * c, 8),
      at("enc4a", 4 * c, 8 * c, 16), at("enc4b", 8 * c, 8 * c, 16),
      at("enc5a", 8 * c, 8 * c, 32), at("enc5b", 8 * c, 8 * c, 32),
      at("up4", 8 * c, 8 * c, 16),   at("iconv4", 16 * c, 8 * c, 16),
      at("up3", 8 * c, 4 * c, 8),    at("iconv3", 8 * c, 4 * c, 8),     at("disp3", 4 * c, 1, 8),
      at("up2", 4 * c, 2 * c, 4),    at("iconv2", 4 * c + 1, 2 * c, 4), at("disp2", 2 * c, 1, 4),
      at("up1", 2 * c, c, 2),        at("iconv1", 2 * c + 1, c, 2),     at("disp1", c, 1, 2),
      at("up0", c, c, 1),            at("iconv0", c + 1, c, 1),         at("disp0", c, 1, 1),
  };
}

std::int64_t gs_depthnet_parameters(const GsDepthNetShape& s) {
  std::int64_t n = 0;
  for (const auto& l : gs_depthnet_layers(s))
    n += static_cast<std::int64_t>(l.out_channels) * l.in_channels * l.kernel * l.kernel + l.out_channels;
  return n;
}

double gs_depthnet_flops(const GsDepthNetShape& s) {
  double n = 0;
  for (const auto& l : gs_depthnet_layers(s))
    n += 2.0 * l.in_channels * l.kernel * l.kernel * l.out_channels * l.out_height * l.out_width;
  return 2 * n;  // a pass per view
}

GsDepthNetImpl::GsDepthNetImpl(const GsDepthNetShape& shape, const ReferenceDisparity& reference)
    : shape_(shape), reference_(reference) {
  // sigmoid(b) = -offset / d_max: the untrained output is the rest disparity,
  // within the appearance loss's reach of a press's few pixels.
  const double rest = std::clamp(-shape.min_disparity_px / shape.d_max_px, 0.01, 0.99);
  for (const auto& l : gs_depthnet_layers(shape)) {
    const bool strided = l.name.rfind("enc", 0) == 0 && l.name.back() == 'a';
    convs_.push_back(register_module(
        l.name, torch::nn::Conv2d(torch::nn::Conv2dOptions(l.in_channels, l.out_channels, l.kernel)
                                      .stride(strided ? 2 : 1)
                                      .padding(l.kernel / 2))));
    if (l.name.rfind("disp", 0) == 0) {
      torch::NoGradGuard no_grad;
      convs_.back()->bias.fill_(std::log(rest / (1 - rest)));
    }
    names_.push_back(l.name);
  }
}

torch::Tensor GsDepthNetImpl::reference_map(bool right_view, std::int64_t row0, std::int64_t height, std::int64_t h,
                                            std::int64_t w) {
  auto& t = maps_[{right_view, row0, height, h, w}];
  if (!t.defined()) {
    const cv::Mat m = reference_.map(right_view, static_cast<int>(row0), static_cast<int>(height), static_cast<int>(h),
                                     static_cast<int>(w));
    t = torch::from_blob(m.data, {1, 1, h, w}, torch::kFloat32).clone();
  }
  return t;
}

torch::Tensor GsDepthNetImpl::gel_mask(bool right_view, std::int64_t row0, std::int64_t height) {
  if (height == 0) height = reference_.left_px.rows - row0;
  auto& t = gels_[{right_view, row0, height}];
  if (!t.defined()) {
    const cv::Mat g = reference_.gel(right_view, static_cast<int>(row0), static_cast<int>(height));
    t = torch::from_blob(g.data, {1, 1, g.rows, g.cols}, torch::kFloat32).clone();
  }
  return t;
}

torch::Tensor matching_costs(const torch::Tensor& view, const torch::Tensor& other, const std::vector<int>& shifts) {
  // A pixel of the view whose disparity is `s` above the rest disparity sees
  // its content in `other` s columns to its left.
  const std::int64_t w = view.size(3);
  int pad = 0;
  for (int s : shifts) pad = std::max(pad, std::abs(s));
  const torch::Tensor padded = F::pad(other, F::PadFuncOptions({pad, pad, 0, 0}).mode(torch::kReplicate));
  std::vector<torch::Tensor> costs;
  for (int s : shifts) costs.push_back((view - padded.narrow(3, pad - s, w)).abs().mean(1, true));
  // The 3 x 3 box average as two passes of three shifted sums: libtorch
  // 1.13's CPU avg_pool2d took 36 ms of a 50 ms cost volume at 256 x 256.
  const torch::Tensor padded_costs = F::pad(torch::cat(costs, 1), F::PadFuncOptions({1, 1, 1, 1}).mode(torch::kReplicate));
  const std::int64_t h = view.size(2);
  const torch::Tensor rows = padded_costs.narrow(3, 0, w) + padded_costs.narrow(3, 1, w) + padded_costs.narrow(3, 2, w);
  return (rows.narrow(2, 0, h) + rows.narrow(2, 1, h) + rows.narrow(2, 2, h)) / 9;
}

std::vector<Disparities> GsDepthNetImpl::forward(const torch::Tensor& left, const torch::Tensor& right,
                                                 std::int64_t row0) {
  auto elu = [](const torch::Tensor& t) { return torch::elu(t); };
  auto up = [](const torch::Tensor& t) {
    return F::interpolate(t, F::InterpolateFuncOptions().scale_factor(std::vector<double>{2, 2}).mode(torch::kNearest));
  };
  const double offset = shape_.min_disparity_px, d_max = shape_.d_max_px;
  std::size_t k = 0;
  auto next = [&](const torch::Tensor& x) { return apply(k++, x); };
  // Pass 1: the left view beside the right one warped onto it by the rest
  // disparity; pass 2: the same for the right view, mirrored.
  const std::int64_t b = left.size(0), h = left.size(2), w = left.size(3);
  if (row0 < 0 || row0 + h > reference_.left_px.rows || w != reference_.left_px.cols)
    throw RunError("GS-DepthNet: rows " + std::to_string(row0) + ".." + std::to_string(row0 + h) + " of " +
                   std::to_string(w) + " px do not lie within the rest disparity's " +
                   std::to_string(reference_.left_px.cols) + " x " + std::to_string(reference_.left_px.rows) + " px");
  const torch::Tensor right_on_left = sample_along_x(right, -reference_map(false, row0, h, h, w));
  const torch::Tensor left_on_right = sample_along_x(left, reference_map(true, row0, h, h, w));
  // Each pass: the view, and the other view warped onto it (pass 2 mirrored).
  const torch::Tensor view = torch::cat({left, right.flip(3)}, 0), other = torch::cat({right_on_left, left_on_right.flip(3)}, 0);
  torch::Tensor x = torch::cat({view - 0.5, other - 0.5, matching_costs(view, other, shape_.cost_shifts())}, 1);
  std::vector<torch::Tensor> skips;
  for (int block = 0; block < 5; ++block) {
    x = elu(next(x));
    x = elu(next(x));
    skips.push_back(x);
  }
  // Decoder: up4/iconv4 without a disparity, then four scales.
  x = elu(next(up(x)));
  x = elu(next(torch::cat({x, skips[3]}, 1)));
  std::vector<Disparities> scales;
  torch::Tensor unit;  // the previous scale's sigmoid output, upsampled
  for (int scale = 3; scale >= 0; --scale) {
    x = elu(next(up(x)));
    std::vector<torch::Tensor> parts{x};
    if (scale > 0) parts.push_back(skips[scale - 1]);
    if (unit.defined()) parts.push_back(unit);
    x = elu(next(torch::cat(parts, 1)));
    const torch::Tensor s = torch::sigmoid(next(x));
    const torch::Tensor relative_left = offset + d_max * s.narrow(0, 0, b);
    const torch::Tensor relative_right = offset + d_max * s.narrow(0, b, b).flip(3);
    const std::int64_t sh = s.size(2), sw = s.size(3);
    scales.push_back({reference_map(false, row0, h, sh, sw) + relative_left,
                      reference_map(true, row0, h, sh, sw) + relative_right,
                      relative_left});
    if (scale > 0) unit = F::interpolate(s, F::InterpolateFuncOptions().scale_factor(std::vector<double>{2, 2})
                                                .mode(torch::kBilinear).align_corners(false));
  }
  return scales;
}

LossTerms gs_depthnet_loss(const std::vector<Disparities>& scales, const torch::Tensor& left, const torch::Tensor& right,
                           const torch::Tensor& contact, const LossWeights& w, const torch::Tensor& gel_left,
                           const torch::Tensor& gel_right) {
  const auto opts = left.options();
  LossTerms t{torch::zeros({}, opts), torch::zeros({}, opts), torch::zeros({}, opts), torch::zeros({}, opts),
              torch::zeros({}, opts)};
  const std::int64_t h = left.size(2), width = left.size(3);
  auto full = [&](const torch::Tensor& d) {
    if (d.size(2) == h && d.size(3) == width) return d;
    return F::interpolate(d, F::InterpolateFuncOptions().size(std::vector<std::int64_t>{h, width})
                                 .mode(torch::kBilinear).align_corners(false));
  };
  for (const auto& scale : scales) {
    const torch::Tensor dl = full(scale.left), dr = full(scale.right);
    const double r = static_cast<double>(width) / static_cast<double>(scale.left.size(3));
    auto at_scale = [&](const torch::Tensor& image) {
      if (r == 1) return image;
      return F::avg_pool2d(image, F::AvgPool2dFuncOptions(static_cast<std::int64_t>(r)));
    };
    if (w.appearance && w.appearance_resolution == AppearanceResolution::Input) {
      const torch::Tensor left_est = sample_along_x(right, -dl), right_est = sample_along_x(left, dr);
      t.appearance = t.appearance + w.w_ap * (appearance_loss(left, left_est, w.alpha, gel_left) +
                                              appearance_loss(right, right_est, w.alpha, gel_right));
    } else if (w.appearance) {
      // In pixels of the scale: the disparity divided by r.
      const torch::Tensor l = at_scale(left), rr = at_scale(right);
      const torch::Tensor left_est = sample_along_x(rr, -scale.left / r), right_est = sample_along_x(l, scale.right / r);
      auto gel_at_scale = [&](const torch::Tensor& g) { return g.defined() ? at_scale(g).round() : g; };
      t.appearance = t.appearance + w.w_ap * (appearance_loss(l, left_est, w.alpha, gel_at_scale(gel_left)) +
                                              appearance_loss(rr, right_est, w.alpha, gel_at_scale(gel_right)));
    }
    if (w.smoothness) {
      t.smoothness = t.smoothness + w.w_ds / r * (smoothness_loss(scale.left, at_scale(left)) +
                                                  smoothness_loss(scale.right, at_scale(right)));
    }
    if (w.lr_consistency) t.lr_consistency = t.lr_consistency + w.w_lr * lr_consistency_loss(dl, dr, gel_left, gel_right);
    if (w.semantic) {
      if (!contact.defined()) throw RunError("gs_depthnet_loss: the semantic term is on, but no contact mask was given");
      // The right view's contact mask is the left one's, moved by the left
      // disparity: near enough for a term of weight 1e-4; the paper applies
      // the left mask (Eq. 6 is written for the left view).
      t.semantic = t.semantic + w.w_se * semantic_loss(full(scale.left_relative), contact);
    }
  }
  t.total = t.appearance + t.smoothness + t.lr_consistency + t.semantic;
  return t;
}

}  // namespace touchcloud::learning
