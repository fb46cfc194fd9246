// The values of a PLY body (after a header checked by ply_header.hpp), read
// one at a time in ASCII, binary little or big endian, never past its end.
// Shared by the cloud and mesh readers.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "io/ply_header.hpp"

namespace touchcloud::ply {

// Where a value is, for an error: row `row` of element `element`.
struct Place {
  const std::string& element;
  std::uint64_t row;
  std::string str() const { return element + " " + std::to_string(row); }
};

class BodyReader {
 public:
  BodyReader(std::string_view body, Format format, const std::filesystem::path& file)
      : body_(body), format_(format), file_(file) {}

  std::size_t remaining() const { return body_.size() - at_; }

  // The next value of type `type` as a double (ASCII parsed as a double).
  double next(Scalar type, const Place& where);

  // The next value rounded once to float: an ASCII float value is parsed as
  // a float (double then float can round twice); any other value converts.
  float next_float(Scalar type, const Place& where);

  // A list length: an integer no larger than the remaining values can fill.
  std::uint64_t next_count(Scalar count_type, Scalar item_type, const Place& where);

  // Reads past every value of one row of `element`.
  void skip_row(const Element& element, const Place& where);

  [[noreturn]] void fail(const std::string& why) const;

 private:
  double next_binary(Scalar type, const Place& where);
  std::string_view next_word(const Place& where);

  std::string_view body_;
  std::size_t at_ = 0;
  Format format_;
  const std::filesystem::path& file_;
};

}  // namespace touchcloud::ply
