#include "touchcloud/learning/tactile_net_pair.hpp"

#include <cmath>

#include "touchcloud/error.hpp"
#include "touchcloud/learning/torch_io.hpp"

namespace touchcloud::learning {

namespace {
double positive_field(const CheckpointHeader& h, const std::string& name, const std::string& file) {
  const auto text = training_field(h, name);
  if (!text) throw InputError(file + ": the " + h.architecture + " checkpoint has no training field '" + name + "'");
  try {
    std::size_t used = 0;
    const double v = std::stod(*text, &used);
    if (used == text->size() && std::isfinite(v) && v > 0) return v;
  } catch (const std::exception&) {
  }
  throw InputError(file + ": training field '" + name + "' is '" + *text + "', not a positive number");
}

// Weights that are NaN or infinite would make every height NaN.
void require_finite(const torch::nn::Module& net, const std::string& file) {
  for (const auto& p : net.named_parameters())
    if (!torch::isfinite(p.value()).all().item<bool>())
      throw InputError(file + ": the weights hold NaN or infinity (" + p.key() + ")");
  for (const auto& b : net.named_buffers())
    if (!torch::isfinite(b.value()).all().item<bool>())
      throw InputError(file + ": the input normalisation holds NaN or infinity (" + b.key() + ")");
}
}  // namespace

std::optional<std::string> training_field(const CheckpointHeader& header, const std::string& name) {
  for (const auto& [n, v] : header.training_fields)
    if (n == name) return v;
  return std::nullopt;
}

TactileNetHeaders TactileNetHeaders::read(const std::filesystem::path& contact_file,
                                          const std::filesystem::path& depth_file) {
  TactileNetHeaders h;
  const CheckpointHeader contact = read_checkpoint_header(contact_file);
  h.contact = TactileNetShape::from_header(contact, TactileNet::Contact, contact_file.string());
  const CheckpointHeader depth = read_checkpoint_header(depth_file);
  h.depth = TactileNetShape::from_header(depth, TactileNet::Depth, depth_file.string());
  if (h.contact.input_width_px != h.depth.input_width_px || h.contact.input_height_px != h.depth.input_height_px)
    throw InputError(depth_file.string() + " is " + depth.describe() + ", but " + contact_file.string() + " is " +
                     contact.describe() + ": the two networks must share the input size");
  h.sensor.sensor = training_field(depth, "sensor").value_or("");
  h.sensor.mm_per_px = positive_field(depth, "mm_per_px", depth_file.string());
  h.sensor.gel_thickness_mm = positive_field(depth, "gel_thickness_mm", depth_file.string());
  return h;
}

TactileNetPair::TactileNetPair(const std::filesystem::path& contact_file, const std::filesystem::path& depth_file)
    : headers_(TactileNetHeaders::read(contact_file, depth_file)) {
  const Checkpoint contact = read_checkpoint(contact_file);
  const Checkpoint depth = read_checkpoint(depth_file);
  contact_ = ContactNet(headers_.contact);
  load_module_bytes(*contact_, contact.blob("weights", contact_file.string()), contact_file.string());
  require_finite(*contact_, contact_file.string());
  contact_->eval();
  depth_ = TactileDepthNet(headers_.depth);
  load_module_bytes(*depth_, depth.blob("weights", depth_file.string()), depth_file.string());
  require_finite(*depth_, depth_file.string());
  depth_->eval();
}

TactilePrediction TactileNetPair::predict(const cv::Mat& image, const cv::Mat& reference) {
  torch::NoGradGuard no_grad;
  const torch::Tensor d = tactile_difference_batch({image}, reference);
  const torch::Tensor p = torch::sigmoid(contact_->forward(d));
  return {tensor_image(p), tensor_image(depth_->forward(d, p))};
}

}  // namespace touchcloud::learning
