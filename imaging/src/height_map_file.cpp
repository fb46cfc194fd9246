#include "touchcloud/imaging/height_map_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include <zlib.h>

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/file_write.hpp"
#include "touchcloud/number_text.hpp"

namespace touchcloud::imaging {

namespace {

std::string extension_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void put_u32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((v >> shift) & 0xFF));
}

// A PNG tEXt chunk: length, type, keyword NUL text, CRC of type and data.
std::string text_chunk(const std::string& keyword, const std::string& text) {
  const std::string body = "tEXt" + keyword + std::string(1, '\0') + text;
  std::string chunk;
  put_u32(chunk, static_cast<std::uint32_t>(body.size() - 4));
  chunk += body;
  put_u32(chunk, static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
  return chunk;
}

constexpr std::size_t kIhdrEnd = 8 + 12 + 13;  // signature, then IHDR (length, type, 13 bytes, CRC)

}  // namespace

std::optional<std::string> height_map_path_problem(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".png" || ext == ".tif" || ext == ".tiff") return std::nullopt;
  return "'" + path + "' must end in .png, .tif or .tiff (a 16-bit height map)";
}

HeightMapFileSummary write_height_map_file(const std::filesystem::path& file, const cv::Mat& height_mm,
                                           const cv::Mat& valid, double mm_per_count) {
  HeightMapFileSummary s;
  cv::Mat counts(height_mm.size(), CV_16UC1);
  const double most = 65535 * mm_per_count;
  const auto counted = [&](int u, int v) { return valid.empty() || valid.at<std::uint8_t>(v, u); };
  // The highest pixel names the scale that would hold the whole map.
  double highest = 0;
  cv::Point at;
  for (int v = 0; v < height_mm.rows; ++v)
    for (int u = 0; u < height_mm.cols; ++u)
      if (counted(u, v) && height_mm.at<float>(v, u) > highest) highest = height_mm.at<float>(v, u), at = {u, v};
  if (highest > most) {
    const auto short_number = [](double x) {
      std::ostringstream out;
      out << x;  // six significant digits: a message, not a record
      return out.str();
    };
    throw InputError("a height of " + short_number(highest) + " mm at pixel (" + std::to_string(at.x) + ", " +
                     std::to_string(at.y) + ") does not fit 16 bits at " + short_number(mm_per_count) +
                     " mm per count (at most " + short_number(most) + " mm): raise mm_per_count to at least " +
                     short_number(highest / 65535));
  }
  for (int v = 0; v < height_mm.rows; ++v)
    for (int u = 0; u < height_mm.cols; ++u) {
      const double h = height_mm.at<float>(v, u);
      std::uint16_t c = 0;
      if (!counted(u, v)) {
        ++s.invalid;
      } else if (h < 0) {
        ++s.below_zero;
      } else {
        c = static_cast<std::uint16_t>(std::lround(h / mm_per_count));
        s.max_height_mm = std::max(s.max_height_mm, h);
      }
      counts.at<std::uint16_t>(v, u) = c;
    }
  const std::string ext = extension_of(file);
  std::vector<uchar> encoded;
  if (!cv::imencode(ext, counts, encoded))
    throw RunError("OpenCV cannot encode a 16-bit " + ext + " image for " + file.string());
  std::string bytes(encoded.begin(), encoded.end());
  if (ext == ".png") bytes.insert(kIhdrEnd, text_chunk(kHeightScaleKeyword, number_text(mm_per_count)));
  write_file(file, bytes);
  return s;
}

std::optional<double> read_height_scale(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t at = 8; at + 12 <= b.size();) {
    const std::uint32_t length = static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 24 |
                                 static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 16 |
                                 static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 8 |
                                 static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3]));
    if (length > b.size() - at - 12) break;
    const std::string type = b.substr(at + 4, 4), data = b.substr(at + 8, length);
    if (type == "tEXt" && data.rfind(std::string(kHeightScaleKeyword) + '\0', 0) == 0)
      return std::stod(data.substr(std::string(kHeightScaleKeyword).size() + 1));
    if (type == "IEND") break;
    at += 12 + length;
  }
  return std::nullopt;
}

}  // namespace touchcloud::imaging
