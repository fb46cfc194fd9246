#include "touchcloud/imaging/picture_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/file_write.hpp"

namespace touchcloud::imaging {

namespace {
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.42;

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}
}  // namespace

std::optional<std::string> picture_path_problem(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") return std::nullopt;
  return "'" + path + "' must end in .png, .jpg or .jpeg (the picture's format)";
}

void write_picture(const std::filesystem::path& file, const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  if (!cv::imencode(extension_of(file.string()), image, bytes))
    throw RunError("OpenCV could not encode the picture " + file.string() + " (" + cv::typeToString(image.type()) +
                   ")");
  write_file(file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void put_text(cv::Mat& image, const std::string& text, cv::Point origin, const cv::Scalar& colour) {
  cv::putText(image, text, origin, kFont, kFontScale, colour, 1, cv::LINE_AA);
}

int text_width(const std::string& text) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, kFontScale, 1, &baseline).width;
}

}  // namespace touchcloud::imaging
