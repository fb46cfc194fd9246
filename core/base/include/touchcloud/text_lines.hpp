// The lines of a text file as editors and spreadsheets write them: a UTF-8
// byte order mark before the first line and a carriage return before each
// line feed (Windows) belong to no line. For the CSV files users edit
// (dataset index, sweep.csv, score manifests).
#pragma once

#include <istream>
#include <string>

namespace touchcloud {

class TextLines {
 public:
  explicit TextLines(std::istream& in) : in_(in) {}

  // The next line into `line`; false at the end.
  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    if (first_ && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    first_ = false;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }

 private:
  std::istream& in_;
  bool first_ = true;
};

}  // namespace touchcloud
