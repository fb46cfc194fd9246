// GS-DepthNet (the GS-DepthNet paper, Section III): an encoder-decoder with skip
// connections that takes a rectified colour pair and outputs left and right
// disparities at four scales (1/8, 1/4, 1/2 and 1 of the input, each double
// the previous), each the gel's rest disparity (reference_disparity.hpp)
// plus min_disparity_px + d_max_px * sigmoid(x), in pixels of the input; and
// its loss module (Eq. 2-6). Each view's disparity comes from one pass of
// the same weights: the view beside the other view warped onto it by the
// rest disparity (the right view's pass mirrored, so that it looks like a
// left view's), so what the network must find is the small shift of a press,
// next to where it looks. Beside the two images the first layer takes
// their matching costs at each whole-pixel shift of the output range (mean
// absolute colour difference, 3 x 3 box-averaged): DispNet-C's correlation
// input (Mayer et al., the paper's reference [24] for its encoder-decoder)
// instead of DispNet-S's bare stacked pair, which learns matching only from
// far more data and steps than a 2-core CPU gives (the paper: 6 h on four
// GPUs; trained here without the costs, the network's error did not move in
// 150 steps, with them it halved). Sized for a CPU: `width` is the first
// encoder block's channel count (the paper's network: 16 M parameters; see
// gs_depthnet_layers()). Includes torch.
#pragma once

#include <cstdint>
#include <map>
#include <tuple>
#include <string>
#include <vector>

#include <torch/torch.h>

#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/reference_disparity.hpp"

namespace touchcloud::learning {

struct GsDepthNetShape {
  int width = 8;                  // channels of the first encoder block; the others 2x, 4x, 8x, 8x
  int input_width_px = 256, input_height_px = 256;  // multiples of 32
  double d_max_px = 12;           // output range above the offset (the paper's d_max)
  double min_disparity_px = -1;   // offset: the smallest disparity relative to the gel at rest

  // The whole-pixel shifts whose matching costs the first layer takes:
  // ceil(min_disparity_px) .. floor(min_disparity_px + d_max_px).
  std::vector<int> cost_shifts() const;

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
// Floating-point operations of one pair at the input size (two passes, one
// per view): 2 per multiply-add of every convolution (activations,
// upsampling, warping and the sigmoid are not counted).
double gs_depthnet_flops(const GsDepthNetShape& shape);

// The first layer's matching costs: for each shift s, the mean absolute
// colour difference between `view` at x and `other` at x - s (replicated
// beyond the edge), box-averaged over 3 x 3; [B, shifts, H, W].
torch::Tensor matching_costs(const torch::Tensor& view, const torch::Tensor& other, const std::vector<int>& shifts);

struct Disparities {
  torch::Tensor left, right;    // [B, 1, h, w], px of the input
  torch::Tensor left_relative;  // left minus the rest disparity (Eq. 6's disparity)
};

class GsDepthNetImpl : public torch::nn::Module {
 public:
  // The output layers' biases start the output at the rest disparity.
  GsDepthNetImpl(const GsDepthNetShape& shape, const ReferenceDisparity& reference);
  // left, right: [B, 3, H, W] in [0, 1], the input's rows [row0, row0 + H)
  // (a band of rows in training; the whole input otherwise). Four scales,
  // coarsest first.
  std::vector<Disparities> forward(const torch::Tensor& left, const torch::Tensor& right, std::int64_t row0 = 0);
  const GsDepthNetShape& shape() const { return shape_; }
  const ReferenceDisparity& reference() const { return reference_; }
  // The rest disparity of one view's input rows [row0, row0 + height) at an
  // h x w scale, [1, 1, h, w] (cached).
  torch::Tensor reference_map(bool right_view, std::int64_t row0, std::int64_t height, std::int64_t h, std::int64_t w);
  // Where the view sees the gel in input rows [row0, row0 + height) (all
  // rows when height is 0), [1, 1, height, W], 1 or 0.
  torch::Tensor gel_mask(bool right_view, std::int64_t row0 = 0, std::int64_t height = 0);

 private:
  GsDepthNetShape shape_;
  ReferenceDisparity reference_;
  std::vector<torch::nn::Conv2d> convs_;
  std::vector<std::string> names_;
  std::map<std::tuple<bool, std::int64_t, std::int64_t, std::int64_t, std::int64_t>, torch::Tensor> maps_;
  std::map<std::tuple<bool, std::int64_t, std::int64_t>, torch::Tensor> gels_;
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
// be undefined only when the semantic term is off; the semantic term takes
// the disparity relative to the gel at rest (0 outside contact). The
// appearance and consistency terms count only the pixels where each view
// sees the gel (`gel_left`, `gel_right`, [1, 1, H, W]; undefined: all): the
// paper's images are all gel, ours show the sensor's dark housing around it,
// where nothing can be matched.
LossTerms gs_depthnet_loss(const std::vector<Disparities>& scales, const torch::Tensor& left,
                           const torch::Tensor& right, const torch::Tensor& contact, const LossWeights& weights,
                           const torch::Tensor& gel_left = {}, const torch::Tensor& gel_right = {});

}  // namespace touchcloud::learning
