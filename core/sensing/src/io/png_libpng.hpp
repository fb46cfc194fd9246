// Every PNG layout the common one (png_rows.hpp) leaves (16-bit, palette,
// 1-, 2- and 4-bit grey, alpha, transparency, interlaced, colour-space
// chunks) decoded by libpng, the library OpenCV's own PNG decoder calls,
// with the transforms OpenCV asks of it for the same flags: the same
// pixels. libpng's errors and warnings are caught here instead of being
// printed on the terminal ("libpng warning: iCCP: known incorrect sRGB
// profile", "libpng error: Not enough image data").
#pragma once

#include <string_view>

#include "png_rows.hpp"

namespace touchcloud::io {

// The image cv::imdecode(png, flags) gives, or in `damage` why not: libpng's
// error, or a size OpenCV refuses. Neither for flags other than
// IMREAD_UNCHANGED, IMREAD_GRAYSCALE and IMREAD_COLOR with IMREAD_ANYDEPTH
// or IMREAD_ANYCOLOR, nor for a file with an EXIF chunk (OpenCV may turn the
// image by its orientation): OpenCV then decodes, once the header's size
// and the data's have been checked. A warning about the image
// data is damage too; others (a colour profile libpng distrusts) are
// dropped. `png` is a whole file whose chunks' lengths and checksums the
// caller has checked.
DecodedPng decode_png_with_libpng(std::string_view png, int flags);

}  // namespace touchcloud::io
