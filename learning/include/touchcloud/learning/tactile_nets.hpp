// The ContactNet/TactileDepthNet report's two networks for a monocular GelSight-type sensor: ContactNet
// (tactile image -> contact probability) and TactileDepthNet (tactile image
// and that probability -> height map, mm), sized for a 2-core CPU. Includes
// torch: network code only.
//
// Where the report is vague, this is what was chosen, and why:
//
// - Input: the image minus the sensor's no-contact reference image, /255,
//   then normalised per channel with the training set's mean and standard
//   deviation (held in the module as buffers, so a checkpoint carries them).
//   The report "normalized the images"; subtracting the reference removes the
//   gel's own shading and vignetting, which otherwise vary more across the
//   pad than a shallow press changes it (the classical method takes the same
//   reference).
// - ContactNet (Figure 1: five convolutions, max pooling, two fully connected
//   layers, dropout, a resize, a transposed convolution, sigmoid): conv1-2
//   (3 x 3, stride 2) to 1/4 of the input, conv3 there, max pooling, conv4,
//   max pooling, conv5 at 1/16; fc1 (dropout 0.5 after it) and fc2 give a
//   coarse contact map of the whole image at 1/16 (the global view, as the
//   coarse stack of the report's reference [1], Eigen et al.), resized to 1/4
//   (bilinear) and concatenated with conv3's features; one transposed
//   convolution (kernel 8, stride 4) brings that to the input size. ReLU
//   between layers; the output's sigmoid is folded into the BCE loss
//   (binary_cross_entropy_with_logits: the same function, stable for large
//   logits). The output's bias starts at the log-odds of the training set's
//   contact share (a few per cent of the pixels; RetinaNet's prior
//   initialisation): from 0 (probability 0.5), Adam at 0.001 takes
//   thousands of steps only to learn how rare contact is.
// - TactileDepthNet (three convolutions, taking the contact prediction: the
//   fine stack of [1] takes the coarse prediction the same way): the image
//   with ContactNet's probability as a fourth channel; conv1 5 x 5 stride 2
//   and 2 x 2 max pooling to 1/4, conv2 5 x 5 dilated 2, conv3 5 x 5
//   dilated 4 to one channel, the height (mm, linear), upsampled bilinearly
//   to the input size. The dilations give a receptive field of about 110
//   input pixels (6.6 mm on a GelSight Mini): the height of a pressed point
//   depends on the slopes around it, not only on its own shading.
// - Losses: BCE for ContactNet; for TactileDepthNet "the average of the
//   matrix norms of order 2 of the difference": per image the Frobenius
//   norm (torch.norm's p = 2 on a matrix, the root of the summed squared
//   errors, mm), averaged over the batch; not the spectral norm.
// - Augmentation (training only): each sample rotated by an angle uniform in
//   [-5, 5] degrees about the image centre (bilinear; the mask nearest;
//   zero outside, i.e. no contact) and flipped left-right with probability
//   0.5, image and targets alike.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <torch/torch.h>

#include "touchcloud/learning/checkpoint.hpp"

namespace touchcloud::learning {

enum class TactileNet { Contact, Depth };

// "contact_net" or "tactile_depthnet": the checkpoint's architecture.
const char* tactile_net_architecture(TactileNet net);

struct TactileNetShape {
  TactileNet net = TactileNet::Contact;
  int width = 8;                                     // base channel count (see tactile_net_layers)
  int input_width_px = 320, input_height_px = 240;   // ContactNet: multiples of 16; TactileDepthNet: of 4

  CheckpointHeader header() const;  // input W x H x 3, arch width
  // The shape a checkpoint describes; InputError naming `file` and both
  // architectures when it is not of `net`, or for a malformed field or size.
  static TactileNetShape from_header(const CheckpointHeader& header, TactileNet net, const std::string& file);
  // Empty when the input size suits the network, else why not.
  std::string size_problem() const;
};

// One layer of a network and what it costs: weights and biases, and the
// floating-point operations of one forward pass (2 per multiply-add;
// activations, pooling, resizing and the sigmoid are not counted).
struct TactileLayer {
  std::string name;  // "conv1", "fc1", "deconv", ...
  int in_channels = 0, out_channels = 0, kernel = 0;
  int out_height = 0, out_width = 0;  // 1 x 1 for a fully connected layer
  std::int64_t parameters = 0;
  double flops = 0;
};
// Every layer, in order, from the shape alone (no network built).
std::vector<TactileLayer> tactile_net_layers(const TactileNetShape& shape);
std::int64_t tactile_net_parameters(const TactileNetShape& shape);
double tactile_net_flops(const TactileNetShape& shape);

// The networks' input from 8-bit BGR images and their reference: (image -
// reference) / 255 as [N, 3, H, W]; `rows` picks which images (all when empty).
torch::Tensor tactile_difference_batch(const std::vector<cv::Mat>& images, const cv::Mat& reference,
                                       const std::vector<std::int64_t>& rows = {});

// Per-channel mean and standard deviation of difference images [N, 3, H, W],
// each [1, 3, 1, 1] (a standard deviation below 1e-6 becomes 1).
std::pair<torch::Tensor, torch::Tensor> channel_statistics(const torch::Tensor& differences);

// (x - mean) / deviation per channel, the two held as buffers ("mean",
// "deviation"): saved with the weights.
class InputNormalisationImpl : public torch::nn::Module {
 public:
  InputNormalisationImpl();
  torch::Tensor forward(const torch::Tensor& x);
  void set(const torch::Tensor& mean, const torch::Tensor& deviation);

 private:
  torch::Tensor mean_, deviation_;
};
TORCH_MODULE(InputNormalisation);

class ContactNetImpl : public torch::nn::Module {
 public:
  explicit ContactNetImpl(const TactileNetShape& shape);
  // difference [B, 3, H, W] -> contact logits [B, 1, H, W] (sigmoid: the probability).
  torch::Tensor forward(const torch::Tensor& difference);
  void set_normalisation(const torch::Tensor& mean, const torch::Tensor& deviation) { input_->set(mean, deviation); }
  // Sets the output's bias to log(p / (1 - p)) of the share p (clamped to
  // [1e-4, 1 - 1e-4]) of contact pixels in the training set.
  void set_contact_prior(double contact_share);
  const TactileNetShape& shape() const { return shape_; }

 private:
  TactileNetShape shape_;
  InputNormalisation input_{nullptr};
  torch::nn::Conv2d conv1_{nullptr}, conv2_{nullptr}, conv3_{nullptr}, conv4_{nullptr}, conv5_{nullptr};
  torch::nn::Linear fc1_{nullptr}, fc2_{nullptr};
  torch::nn::Dropout dropout_{nullptr};
  torch::nn::ConvTranspose2d deconv_{nullptr};
};
TORCH_MODULE(ContactNet);

class TactileDepthNetImpl : public torch::nn::Module {
 public:
  explicit TactileDepthNetImpl(const TactileNetShape& shape);
  // difference [B, 3, H, W], contact probability [B, 1, H, W] -> height [B, 1, H, W], mm.
  torch::Tensor forward(const torch::Tensor& difference, const torch::Tensor& contact_probability);
  void set_normalisation(const torch::Tensor& mean, const torch::Tensor& deviation) { input_->set(mean, deviation); }
  const TactileNetShape& shape() const { return shape_; }

 private:
  TactileNetShape shape_;
  InputNormalisation input_{nullptr};
  torch::nn::Conv2d conv1_{nullptr}, conv2_{nullptr}, conv3_{nullptr};
};
TORCH_MODULE(TactileDepthNet);

// Mean over the batch of BCE of the logits against the mask (1: contact).
torch::Tensor contact_loss(const torch::Tensor& logits, const torch::Tensor& mask);
// Mean over the batch of each image's Frobenius norm of (height - truth), mm.
torch::Tensor depth_loss(const torch::Tensor& height_mm, const torch::Tensor& truth_mm);

struct TactileAugmentation {
  double max_rotation_deg = 5;    // the report's +-5 degrees
  double flip_probability = 0.5;  // left-right, the report's 50 %
};

// The same random rotation and flip per sample of every tensor [B, C, H, W]
// of `bilinear` (images, heights) and `nearest` (masks), drawn from `rng`
// (raw draws: the same on every standard library).
void augment(std::vector<torch::Tensor*> bilinear, std::vector<torch::Tensor*> nearest,
             const TactileAugmentation& augmentation, std::mt19937_64& rng);

}  // namespace touchcloud::learning
