// Between libtorch and the rest: a module's weights (and an optimiser's
// state) as bytes for a checkpoint blob, and OpenCV images as a batch
// tensor. Includes torch: only network code includes this header.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <torch/torch.h>

namespace touchcloud::learning {

std::string module_bytes(const torch::nn::Module& module);
// InputError naming `where` when the bytes do not load into `module` (a
// corrupt blob, or weights of other shapes).
void load_module_bytes(torch::nn::Module& module, const std::string& bytes, const std::string& where);
std::string optimizer_bytes(const torch::optim::Optimizer& optimizer);
void load_optimizer_bytes(torch::optim::Optimizer& optimizer, const std::string& bytes, const std::string& where);

// Images of one size and type (8-bit: scaled to [0, 1]; 32-bit float: as
// they are) as a float tensor [N, C, H, W]; `rows` picks which (all when empty).
torch::Tensor image_batch(const std::vector<cv::Mat>& images, const std::vector<std::int64_t>& rows = {});
// One [C, H, W] or [1, C, H, W] float tensor back to a CV_32FC(C) image.
cv::Mat tensor_image(const torch::Tensor& image);

}  // namespace touchcloud::learning
