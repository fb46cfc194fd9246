// The words of one line of a text header (PCD, PLY): runs of characters
// between spaces, tabs and carriage returns.
#pragma once

#include <string_view>
#include <vector>

namespace touchcloud::io_text {

inline std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  std::size_t at = 0;
  while (at < line.size()) {
    while (at < line.size() && blank(line[at])) ++at;
    const std::size_t start = at;
    while (at < line.size() && !blank(line[at])) ++at;
    if (at > start) words.push_back(line.substr(start, at - start));
  }
  return words;
}

}  // namespace touchcloud::io_text
