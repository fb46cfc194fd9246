// GS-DepthNet (seed 000, Section III): an encoder-decoder with skip
// connections that takes a rectified colour pair and outputs left and right
// disparities at four scales (1/8, 1/4, 1/2 and 1 of the input, each double
// the previous), each min_disparity_px + d_max_px * sigmoid(x) in pixels of
// the input; and its loss module (Eq. 2-6). Sized for a CPU: `width` is the
// first encoder block's channel count (the paper's network: 16 M
// parameters; width 8 here: see gs_depthnet_layers()). Includes torch.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <torch/torch.h>

#include "touchcloud/learning/checkpoint.hpp"

namespace touchcloud::learning {

struct GsDepthNetShape {
  int width = 8;                  // channels of the first encoder block; the others 2x, 4x, 8x, 8x
  int input_width_px = 256, input_height_px = 256;  // multiples of 32
  double d_max_px = 12;           // output range above the offset (the paper's d_max)
  double min_disparity_px = 0;    // offset: the smallest disparity the network can output

  // The checkpoint header this shape writes and expects (architecture
  // "gs_depthnet", input W x H x 6).
  CheckpointHeader header() const;
  // The shape a checkpoint header describes; InputError naming `file` for
  // another architecture or a malformed field.
  static GsDepthNetShape from_header(const CheckpointHeader& header, const std::string& file);
};

// One convolution of the network: what its parameter count and FLOPs follow from.
struct ConvLayer {
  std::string name;
  int in_channels, out_channels, kernel, out_height, out_width;
};
// Every convolution, in order, from the shape alone (no network built).
std::vector<ConvLayer> gs_depthnet_layers(const GsDepthNetShape& shape);
// Weights and biases of those layers.
std::int64_t gs_depthnet_parameters(const GsDepthNetShape& shape);
// Floating-point operations of one forward pass at the input size: 2 per
// multiply-add of every convolution (activations, upsampling and the
// sigmoid are not counted).
double gs_depthnet_flops(const GsDepthNetShape& shape);

struct Disparities {
  torch::Tensor left, right;  // [B, 1, h, w], px of the input
};

class GsDepthNetImpl : public torch::nn::Module {
 public:
  explicit GsDepthNetImpl(const GsDepthNetShape& shape);
  // left, right: [B, 3, H, W] in [0, 1]. Four scales, coarsest first.
  std::vector<Disparities> forward(const torch::Tensor& left, const torch::Tensor& right);
  const GsDepthNetShape& shape() const { return shape_; }

 private:
  GsDepthNetShape shape_;
  std::vector<torch::nn::Conv2d> convs_;
  std::vector<std::string> names_;
  torch::nn::Conv2d conv(const std::string& name, int in, int out, int stride = 1);
  torch::Tensor apply(std::size_t i, const torch::Tensor& x) { return convs_[i]->forward(x); }
};
TORCH_MODULE(GsDepthNet);

// Where the appearance term compares a scale's reconstruction: at the input
// resolution, the disparities upsampled (the paper, after Monodepth2), or at
// the scale's own resolution, the images downsampled (Monodepth's): there a
// pixel spans r input pixels, so a coarse scale's term still pulls a
// disparity that is many input pixels off toward the match.
enum class AppearanceResolution { Input, Scale };

struct LossWeights {
  double w_ap = 1, alpha = 0.85, w_ds = 0.01, w_lr = 1, w_se = 1e-4;
  bool appearance = true, smoothness = true, lr_consistency = true, semantic = true;
  AppearanceResolution appearance_resolution = AppearanceResolution::Input;
};

struct LossTerms {
  torch::Tensor total, appearance, smoothness, lr_consistency, semantic;  // summed over scales, weighted
};

// The loss module at every scale, each scale's disparities upsampled to the
// input resolution for the appearance, consistency and semantic terms, the
// smoothness term at the scale's own resolution with weight w_ds / r (r:
// the scale's down-scaling factor). `contact` [B, 1, H, W] (1: contact) may
// be undefined only when the semantic term is off. `rest_px`: Eq. 6's zero.
LossTerms gs_depthnet_loss(const std::vector<Disparities>& scales, const torch::Tensor& left,
                           const torch::Tensor& right, const torch::Tensor& contact, const LossWeights& weights,
                           double rest_px);

}  // namespace touchcloud::learning
