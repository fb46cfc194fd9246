#include "image_pairs.hpp"

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/io/image_file.hpp"
#include "touchcloud/run_context.hpp"

namespace fs = std::filesystem;

namespace touchcloud::board_image_corners {

namespace {

std::string numbered(std::string pattern, std::size_t i) {
  const std::string field = kIterationField;
  for (auto at = pattern.find(field); at != std::string::npos; at = pattern.find(field, at))
    pattern.replace(at, field.size(), std::to_string(i));
  return pattern;
}

bool file_exists(const fs::path& file) {
  std::error_code ec;
  return fs::exists(file, ec);
}

std::string absolute_text(const fs::path& file) {
  std::error_code ec;
  const fs::path a = fs::absolute(file, ec);
  return (ec ? file : a).lexically_normal().string();
}

}  // namespace

std::vector<ImagePair> list_image_pairs(const std::string& left_pattern, const std::string& right_pattern) {
  const bool sequence = left_pattern.find(kIterationField) != std::string::npos;
  if (sequence != (right_pattern.find(kIterationField) != std::string::npos))
    throw InputError("the left and right image patterns must both hold '{iteration}' or neither does ('" +
                     left_pattern + "', '" + right_pattern + "')");
  std::vector<ImagePair> pairs;
  for (std::size_t i = 0;; ++i) {
    ImagePair pair{numbered(left_pattern, i), numbered(right_pattern, i)};
    if (!file_exists(pair.left)) {
      if (i == 0) throw InputError("left image " + absolute_text(pair.left) + " does not exist");
      if (file_exists(pair.right))
        throw InputError("right image " + absolute_text(pair.right) + " has no left image (" +
                         absolute_text(pair.left) + " does not exist)");
      break;
    }
    if (!file_exists(pair.right))
      throw InputError("left image " + absolute_text(pair.left) + " has no right image (" +
                       absolute_text(pair.right) + " does not exist)");
    pairs.push_back(std::move(pair));
    if (!sequence) break;
  }
  return pairs;
}

cv::Mat read_grey_image(const fs::path& file) { return read_image_file(file, cv::IMREAD_GRAYSCALE, "image " + absolute_text(file)); }

}  // namespace touchcloud::board_image_corners
