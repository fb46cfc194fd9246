#include "touchcloud/learning/torch_io.hpp"

#include <map>
#include <sstream>
#include <vector>

#include "touchcloud/error.hpp"
#include "touchcloud/library_versions.hpp"

namespace touchcloud::learning {

namespace {
// Recorded in summary.json's versions whenever a network plugin loads this library.
const LibraryVersion torch_version("libtorch", TORCH_VERSION);
}  // namespace

std::string module_bytes(const torch::nn::Module& module) {
  torch::serialize::OutputArchive archive;
  module.save(archive);
  std::ostringstream out;
  archive.save_to(out);
  return out.str();
}

namespace {

std::map<std::string, std::vector<std::int64_t>> tensor_shapes(const torch::nn::Module& module) {
  std::map<std::string, std::vector<std::int64_t>> shapes;
  for (const auto& p : module.named_parameters()) shapes[p.key()] = p.value().sizes().vec();
  for (const auto& b : module.named_buffers()) shapes[b.key()] = b.value().sizes().vec();
  return shapes;
}

std::string shape_text(const std::vector<std::int64_t>& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + "]";
}

}  // namespace

void load_module_bytes(torch::nn::Module& module, const std::string& bytes, const std::string& where) {
  // libtorch's archive replaces each tensor whatever its shape: weights of
  // another width than the header's (which built `module`) would load.
  const auto built = tensor_shapes(module);
  try {
    std::istringstream in(bytes);
    torch::serialize::InputArchive archive;
    archive.load_from(in);
    module.load(archive);
  } catch (const c10::Error& e) {
    const std::string what = e.what_without_backtrace();
    throw InputError(where + ": the weights do not load (" + what.substr(0, what.find('\n')) + ")");
  }
  for (const auto& [name, shape] : tensor_shapes(module)) {
    const auto it = built.find(name);
    if (it != built.end() && it->second != shape)
      throw InputError(where + ": the weights do not fit the network its header describes: '" + name + "' is " +
                       shape_text(shape) + ", the header's network needs " + shape_text(it->second));
  }
}

std::string optimizer_bytes(const torch::optim::Optimizer& optimizer) {
  torch::serialize::OutputArchive archive;
  optimizer.save(archive);
  std::ostringstream out;
  archive.save_to(out);
  return out.str();
}

void load_optimizer_bytes(torch::optim::Optimizer& optimizer, const std::string& bytes, const std::string& where) {
  try {
    std::istringstream in(bytes);
    torch::serialize::InputArchive archive;
    archive.load_from(in);
    optimizer.load(archive);
  } catch (const c10::Error& e) {
    const std::string what = e.what_without_backtrace();
    throw InputError(where + ": the optimiser state does not load (" + what.substr(0, what.find('\n')) + ")");
  }
}

torch::Tensor image_batch(const std::vector<cv::Mat>& images, const std::vector<std::int64_t>& rows) {
  std::vector<std::int64_t> pick = rows;
  if (pick.empty())
    for (std::size_t i = 0; i < images.size(); ++i) pick.push_back(static_cast<std::int64_t>(i));
  if (pick.empty()) throw RunError("image_batch: no images");
  const cv::Mat& first = images.at(static_cast<std::size_t>(pick.front()));
  const int c = first.channels();
  torch::Tensor batch = torch::empty({static_cast<std::int64_t>(pick.size()), first.rows, first.cols, c}, torch::kFloat32);
  for (std::size_t k = 0; k < pick.size(); ++k) {
    const cv::Mat& image = images.at(static_cast<std::size_t>(pick[k]));
    if (image.size() != first.size() || image.type() != first.type())
      throw RunError("image_batch: images of different sizes or types in one batch");
    cv::Mat f;
    image.convertTo(f, CV_MAKETYPE(CV_32F, c), image.depth() == CV_8U ? 1.0 / 255.0 : 1.0);
    if (!f.isContinuous()) f = f.clone();
    std::memcpy(batch[static_cast<std::int64_t>(k)].data_ptr<float>(), f.ptr<float>(), f.total() * c * sizeof(float));
  }
  return batch.permute({0, 3, 1, 2}).contiguous();
}

cv::Mat tensor_image(const torch::Tensor& image) {
  torch::Tensor t = image.detach().to(torch::kFloat32);
  if (t.dim() == 4) t = t[0];
  t = t.permute({1, 2, 0}).contiguous();
  const int h = static_cast<int>(t.size(0)), w = static_cast<int>(t.size(1)), c = static_cast<int>(t.size(2));
  cv::Mat out(h, w, CV_MAKETYPE(CV_32F, c));
  std::memcpy(out.ptr<float>(), t.data_ptr<float>(), static_cast<std::size_t>(h) * w * c * sizeof(float));
  return out;
}

}  // namespace touchcloud::learning
