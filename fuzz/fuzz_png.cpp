// PNG files through read_image_file (chunk checksums, then the common layout
// inflated without libpng, every other one decoded by libpng with its
// messages caught): an image or an InputError, whatever the bytes;
// and where both read it, the pixels OpenCV's own decoder gives, or a crash.
// Each chunk's CRC is set right first, so that mutations reach the decoders
// rather than stopping at the checksum.
#include <libdeflate.h>
#include <opencv2/imgcodecs.hpp>

#include <string>

#include "fuzz_input_file.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/io/image_file.hpp"

namespace {

void set_checksums(std::string& png) {
  const auto u32 = [&](std::size_t at) {
    return static_cast<std::size_t>(static_cast<unsigned char>(png[at])) << 24 |
           static_cast<std::size_t>(static_cast<unsigned char>(png[at + 1])) << 16 |
           static_cast<std::size_t>(static_cast<unsigned char>(png[at + 2])) << 8 |
           static_cast<unsigned char>(png[at + 3]);
  };
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::size_t length = u32(at);
    if (length > png.size() - at - 12) return;
    const std::uint32_t crc = libdeflate_crc32(0, png.data() + at + 4, length + 4);
    for (int i = 0; i < 4; ++i) png[at + 8 + length + i] = static_cast<char>(crc >> (24 - 8 * i));
    at += 12 + length;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (bytes.compare(0, 8, "\x89PNG\r\n\x1A\n") == 0) set_checksums(bytes);
  const auto& file = touchcloud::fuzz::input_file(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), ".png");
  for (int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_COLOR}) {
    cv::Mat ours;
    try {
      ours = touchcloud::read_image_file(file, flags);
    } catch (const touchcloud::InputError&) {
      continue;
    }
    const cv::Mat theirs = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, bytes.data()), flags);
    if (!theirs.empty() && (theirs.type() != ours.type() || theirs.size() != ours.size() ||
                            cv::norm(theirs, ours, cv::NORM_INF) != 0))
      __builtin_trap();
  }
  return 0;
}
