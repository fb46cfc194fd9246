// Reading image files for every stage and library that takes images from
// disk. Needs OpenCV: link touchcloud_image_files.
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace touchcloud {

// The image as cv::imread(file, flags) decodes it, after checks that keep
// a damaged file from passing as an image or a decoder's complaint from
// reaching the terminal: a JPEG must decode without a single libjpeg
// warning (a file cut short would have its missing part filled with
// grey), a PNG's chunks must be whole with valid checksums up to IEND and
// libpng must decode it without an error (its warnings are dropped, never
// printed), a BMP must hold the pixel rows its header declares, and a TIFF
// of floating-point samples is refused where an 8-bit image is asked for.
// InputError otherwise, and when the file is missing, not a regular file,
// or in none of the formats read (PNG, JPEG, TIFF, BMP, PNM, WebP: the
// other decoders OpenCV brings print on the terminal, and no tactile
// camera writes their formats): "NAME cannot be read: why", where
// `name` says which file (default: "the image FILE").
cv::Mat read_image_file(const std::filesystem::path& file, int flags, const std::string& name = {});

// An 8-bit BGR colour image (CV_8UC3; an alpha channel is dropped), read
// with read_image_file's checks. InputError, naming the file, for a grey
// image (colour is needed: a GelSight-type image's colours are its
// gradients) and for 16-bit samples (converting them would hide a wrong
// export), instead of OpenCV's silent conversion.
cv::Mat read_colour_image_file(const std::filesystem::path& file, const std::string& name = {});

}  // namespace touchcloud
