#include "touchcloud/learning/tactile_nets.hpp"

#include <algorithm>
#include <cmath>

#include "touchcloud/error.hpp"
#include "touchcloud/learning/torch_io.hpp"
#include "touchcloud/version.hpp"

namespace touchcloud::learning {

namespace F = torch::nn::functional;

namespace {
constexpr double kDropout = 0.5;  // after fc1 (the report gives no rate; AlexNet's and Eigen's coarse stack's)

TactileLayer conv(const std::string& name, int in, int out, int kernel, int out_height, int out_width) {
  TactileLayer l{name, in, out, kernel, out_height, out_width};
  l.parameters = static_cast<std::int64_t>(in) * out * kernel * kernel + out;
  l.flops = 2.0 * in * kernel * kernel * out * out_height * out_width;
  return l;
}

TactileLayer fully_connected(const std::string& name, int in, int out) {
  TactileLayer l{name, in, out, 1, 1, 1};
  l.parameters = static_cast<std::int64_t>(in) * out + out;
  l.flops = 2.0 * in * out;
  return l;
}

// A transposed convolution of stride `stride` to out_height x out_width:
// every input pixel spreads kernel^2 x out multiply-adds.
TactileLayer transposed(const std::string& name, int in, int out, int kernel, int stride, int out_height,
                        int out_width) {
  TactileLayer l{name, in, out, kernel, out_height, out_width};
  l.parameters = static_cast<std::int64_t>(in) * out * kernel * kernel + out;
  l.flops = 2.0 * in * kernel * kernel * out * (out_height / stride) * (out_width / stride);
  return l;
}

torch::nn::Conv2d make_conv(int in, int out, int kernel, int stride = 1, int dilation = 1) {
  return torch::nn::Conv2d(torch::nn::Conv2dOptions(in, out, kernel)
                               .stride(stride)
                               .dilation(dilation)
                               .padding(dilation * (kernel / 2)));
}

torch::Tensor resized(const torch::Tensor& x, std::int64_t height, std::int64_t width) {
  return F::interpolate(x, F::InterpolateFuncOptions()
                               .size(std::vector<std::int64_t>{height, width})
                               .mode(torch::kBilinear)
                               .align_corners(false));
}
}  // namespace

const char* tactile_net_architecture(TactileNet net) {
  return net == TactileNet::Contact ? "contact_net" : "tactile_depthnet";
}

CheckpointHeader TactileNetShape::header() const {
  CheckpointHeader h;
  h.architecture = tactile_net_architecture(net);
  h.toolkit_version = kVersion;
  h.input_width_px = input_width_px;
  h.input_height_px = input_height_px;
  h.input_channels = 3;
  h.architecture_fields = {{"width", std::to_string(width)}};
  return h;
}

std::string TactileNetShape::size_problem() const {
  const int multiple = net == TactileNet::Contact ? 16 : 4;
  if (input_width_px % multiple || input_height_px % multiple || input_width_px < multiple ||
      input_height_px < multiple)
    return std::string(tactile_net_architecture(net)) + " needs both image sides positive multiples of " +
           std::to_string(multiple) + " px; the input is " + std::to_string(input_width_px) + " x " +
           std::to_string(input_height_px) + " px";
  return "";
}

TactileNetShape TactileNetShape::from_header(const CheckpointHeader& h, TactileNet net, const std::string& file) {
  if (h.architecture != tactile_net_architecture(net))
    throw InputError(file + ": the checkpoint is " + h.describe() + "; this needs a " + tactile_net_architecture(net) +
                     " checkpoint");
  TactileNetShape s;
  s.net = net;
  s.input_width_px = h.input_width_px;
  s.input_height_px = h.input_height_px;
  const std::string& width = h.field("width", file);
  try {
    std::size_t used = 0;
    s.width = std::stoi(width, &used);
    if (used != width.size()) s.width = 0;
  } catch (const std::exception&) {
    s.width = 0;
  }
  if (s.width < 1 || h.input_channels != 3 || !s.size_problem().empty())
    throw InputError(file + ": the checkpoint's " + h.describe() + " is not a valid " + tactile_net_architecture(net) +
                     " (width a whole number >= 1, 3 channels; " +
                     (s.size_problem().empty() ? "sides as the network needs" : s.size_problem()) + ")");
  return s;
}

std::vector<TactileLayer> tactile_net_layers(const TactileNetShape& s) {
  const int c = s.width, h = s.input_height_px, w = s.input_width_px;
  if (s.net == TactileNet::Contact) {
    const int coarse = (h / 16) * (w / 16);
    return {conv("conv1", 3, c, 3, h / 2, w / 2),
            conv("conv2", c, 2 * c, 3, h / 4, w / 4),
            conv("conv3", 2 * c, 2 * c, 3, h / 4, w / 4),
            conv("conv4", 2 * c, 4 * c, 3, h / 8, w / 8),
            conv("conv5", 4 * c, c, 3, h / 16, w / 16),
            fully_connected("fc1", c * coarse, 8 * c),
            fully_connected("fc2", 8 * c, coarse),
            transposed("deconv", 2 * c + 1, 1, 8, 4, h, w)};
  }
  return {conv("conv1", 4, 2 * c, 5, h / 2, w / 2),
          conv("conv2", 2 * c, 2 * c, 5, h / 4, w / 4),
          conv("conv3", 2 * c, 1, 5, h / 4, w / 4)};
}

std::int64_t tactile_net_parameters(const TactileNetShape& shape) {
  std::int64_t n = 0;
  for (const auto& l : tactile_net_layers(shape)) n += l.parameters;
  return n;
}

double tactile_net_flops(const TactileNetShape& shape) {
  double n = 0;
  for (const auto& l : tactile_net_layers(shape)) n += l.flops;
  return n;
}

torch::Tensor tactile_difference_batch(const std::vector<cv::Mat>& images, const cv::Mat& reference,
                                       const std::vector<std::int64_t>& rows) {
  return image_batch(images, rows) - image_batch({reference});
}

std::pair<torch::Tensor, torch::Tensor> channel_statistics(const torch::Tensor& d) {
  const torch::Tensor mean = d.mean({0, 2, 3}, true);
  torch::Tensor deviation = (d - mean).pow(2).mean({0, 2, 3}, true).sqrt();
  deviation = torch::where(deviation < 1e-6, torch::ones_like(deviation), deviation);
  return {mean, deviation};
}

InputNormalisationImpl::InputNormalisationImpl() {
  mean_ = register_buffer("mean", torch::zeros({1, 3, 1, 1}));
  deviation_ = register_buffer("deviation", torch::ones({1, 3, 1, 1}));
}

torch::Tensor InputNormalisationImpl::forward(const torch::Tensor& x) { return (x - mean_) / deviation_; }

void InputNormalisationImpl::set(const torch::Tensor& mean, const torch::Tensor& deviation) {
  torch::NoGradGuard no_grad;
  mean_.copy_(mean);
  deviation_.copy_(deviation);
}

ContactNetImpl::ContactNetImpl(const TactileNetShape& shape) : shape_(shape) {
  input_ = register_module("input", InputNormalisation());
  const auto layers = tactile_net_layers(shape);
  auto at = [&](int i) { return layers[static_cast<std::size_t>(i)]; };
  conv1_ = register_module("conv1", make_conv(at(0).in_channels, at(0).out_channels, 3, 2));
  conv2_ = register_module("conv2", make_conv(at(1).in_channels, at(1).out_channels, 3, 2));
  conv3_ = register_module("conv3", make_conv(at(2).in_channels, at(2).out_channels, 3));
  conv4_ = register_module("conv4", make_conv(at(3).in_channels, at(3).out_channels, 3));
  conv5_ = register_module("conv5", make_conv(at(4).in_channels, at(4).out_channels, 3));
  fc1_ = register_module("fc1", torch::nn::Linear(at(5).in_channels, at(5).out_channels));
  dropout_ = register_module("dropout", torch::nn::Dropout(kDropout));
  fc2_ = register_module("fc2", torch::nn::Linear(at(6).in_channels, at(6).out_channels));
  // (H/4 - 1) * 4 - 2 * 2 + 8 = H: the input size again.
  deconv_ = register_module("deconv", torch::nn::ConvTranspose2d(
                                          torch::nn::ConvTranspose2dOptions(at(7).in_channels, 1, 8).stride(4).padding(2)));
}

void ContactNetImpl::set_contact_prior(double contact_share) {
  const double p = std::clamp(contact_share, 1e-4, 1 - 1e-4);
  torch::NoGradGuard no_grad;
  deconv_->bias.fill_(std::log(p / (1 - p)));
}

torch::Tensor ContactNetImpl::forward(const torch::Tensor& difference) {
  const std::int64_t h = difference.size(2), w = difference.size(3);
  torch::Tensor x = input_(difference);
  x = torch::relu(conv1_(x));
  x = torch::relu(conv2_(x));
  const torch::Tensor fine = torch::relu(conv3_(x));
  x = torch::relu(conv4_(F::max_pool2d(fine, F::MaxPool2dFuncOptions(2))));
  x = torch::relu(conv5_(F::max_pool2d(x, F::MaxPool2dFuncOptions(2))));
  x = dropout_(torch::relu(fc1_(x.flatten(1))));
  const torch::Tensor coarse = torch::relu(fc2_(x)).view({-1, 1, h / 16, w / 16});
  return deconv_(torch::cat({fine, resized(coarse, h / 4, w / 4)}, 1));
}

TactileDepthNetImpl::TactileDepthNetImpl(const TactileNetShape& shape) : shape_(shape) {
  input_ = register_module("input", InputNormalisation());
  const int c = 2 * shape.width;
  conv1_ = register_module("conv1", make_conv(4, c, 5, 2));
  conv2_ = register_module("conv2", make_conv(c, c, 5, 1, 2));
  conv3_ = register_module("conv3", make_conv(c, 1, 5, 1, 4));
}

torch::Tensor TactileDepthNetImpl::forward(const torch::Tensor& difference, const torch::Tensor& contact_probability) {
  const std::int64_t h = difference.size(2), w = difference.size(3);
  torch::Tensor x = torch::cat({input_(difference), contact_probability}, 1);
  x = F::max_pool2d(torch::relu(conv1_(x)), F::MaxPool2dFuncOptions(2));
  x = torch::relu(conv2_(x));
  return resized(conv3_(x), h, w);
}

torch::Tensor contact_loss(const torch::Tensor& logits, const torch::Tensor& mask) {
  return F::binary_cross_entropy_with_logits(logits, mask);
}

torch::Tensor depth_loss(const torch::Tensor& height_mm, const torch::Tensor& truth_mm) {
  return (height_mm - truth_mm).pow(2).sum({1, 2, 3}).sqrt().mean();
}

void augment(std::vector<torch::Tensor*> bilinear, std::vector<torch::Tensor*> nearest,
             const TactileAugmentation& a, std::mt19937_64& rng) {
  const torch::Tensor* first = bilinear.empty() ? nearest.front() : bilinear.front();
  const std::int64_t b = first->size(0), h = first->size(2), w = first->size(3);
  constexpr double kPi = 3.14159265358979323846;
  auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };  // [0, 1)
  torch::Tensor theta = torch::zeros({b, 2, 3});
  auto t = theta.accessor<float, 3>();
  const double aspect = static_cast<double>(h) / static_cast<double>(w);
  for (std::int64_t i = 0; i < b; ++i) {
    const double angle = (2 * uniform() - 1) * a.max_rotation_deg * kPi / 180;
    const double flip = uniform() < a.flip_probability ? -1 : 1;
    // Output (x, y), normalised to [-1, 1] on each axis, samples the input at
    // the rotation of (flip x, y) in pixel units.
    t[i][0][0] = static_cast<float>(std::cos(angle) * flip);
    t[i][0][1] = static_cast<float>(-std::sin(angle) * aspect);
    t[i][1][0] = static_cast<float>(std::sin(angle) / aspect * flip);
    t[i][1][1] = static_cast<float>(std::cos(angle));
  }
  const torch::Tensor grid = F::affine_grid(theta, {b, 1, h, w}, false);
  const auto options = F::GridSampleFuncOptions().padding_mode(torch::kZeros).align_corners(false);
  for (torch::Tensor* x : bilinear) *x = F::grid_sample(*x, grid, F::GridSampleFuncOptions(options).mode(torch::kBilinear));
  for (torch::Tensor* x : nearest) *x = F::grid_sample(*x, grid, F::GridSampleFuncOptions(options).mode(torch::kNearest));
}

}  // namespace touchcloud::learning
