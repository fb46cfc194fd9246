// Pictures written for people (and a run's report): a PNG or JPEG file, and
// the text drawn on them.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace touchcloud::imaging {

// Why `path` cannot name a picture (its extension is not .png, .jpg or
// .jpeg), or nothing: for a parameter rule.
std::optional<std::string> picture_path_problem(const std::string& path);

// Encodes `image` (8-bit BGR) by `file`'s extension and writes it; RunError
// when OpenCV cannot encode it or the file cannot be written.
void write_picture(const std::filesystem::path& file, const cv::Mat& image);

// One line of text, its baseline's left end at `origin` (OpenCV's Hershey
// font, about 10 px high).
void put_text(cv::Mat& image, const std::string& text, cv::Point origin, const cv::Scalar& colour);
// Width in pixels of `text` as put_text draws it.
int text_width(const std::string& text);

inline const cv::Scalar kTextColour{30, 30, 30};
inline const cv::Scalar kPaper{255, 255, 255};

}  // namespace touchcloud::imaging
