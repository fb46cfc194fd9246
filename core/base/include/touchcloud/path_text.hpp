// Paths in messages: a "does not exist" names the absolute path it tried, so
// a user sees which folder a relative path was taken from.
#pragma once

#include <filesystem>
#include <string>

namespace touchcloud {

// `path` made absolute against the current directory and normalised; as
// given if that fails.
inline std::string absolute_text(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path abs = std::filesystem::absolute(path, ec);
  return ec ? path.string() : abs.lexically_normal().string();
}

}  // namespace touchcloud
