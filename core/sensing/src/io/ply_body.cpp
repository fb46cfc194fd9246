#include "io/ply_body.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>

#include "touchcloud/error.hpp"

namespace touchcloud::ply {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

bool is_integer(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

template <class T>
double load(const unsigned char* raw) {
  T v;
  std::memcpy(&v, raw, sizeof v);
  return static_cast<double>(v);
}

}  // namespace

void BodyReader::fail(const std::string& why) const { throw InputError(file_.string() + ": " + why); }

double BodyReader::next(Scalar type, const Place& where) {
  if (format_ != Format::Ascii) return next_binary(type, where);
  const std::string_view word = next_word(where);
  const char* first = word.data();
  const char* last = word.data() + word.size();
  double v = 0;
  std::from_chars_result r{};
  if (is_integer(type)) {
    std::int64_t i = 0;
    r = std::from_chars(first, last, i);
    v = static_cast<double>(i);
  } else {
    r = std::from_chars(first, last, v);
  }
  if (r.ec != std::errc() || r.ptr != last)
    fail(where.str() + ": '" + std::string(word.substr(0, 40)) + "' is not " +
         (is_integer(type) ? "an integer" : "a number"));
  return v;
}

float BodyReader::next_float(Scalar type, const Place& where) {
  if (format_ != Format::Ascii || type != Scalar::Float32) return static_cast<float>(next(type, where));
  const std::string_view word = next_word(where);
  float v = 0;
  const auto r = std::from_chars(word.data(), word.data() + word.size(), v);
  if (r.ec != std::errc() || r.ptr != word.data() + word.size())
    fail(where.str() + ": '" + std::string(word.substr(0, 40)) + "' is not a number");
  return v;
}

std::uint64_t BodyReader::next_count(Scalar count_type, Scalar item_type, const Place& where) {
  const double n = next(count_type, where);
  if (n < 0 || n != static_cast<double>(static_cast<std::uint64_t>(n)))
    fail(where.str() + " has a negative or fractional list length");
  const std::uint64_t per_item = format_ == Format::Ascii ? 2 : size_of(item_type);
  if (static_cast<std::uint64_t>(n) > (remaining() + 1) / per_item)
    fail(where.str() + " declares a list of " + std::to_string(static_cast<std::uint64_t>(n)) +
         " values, more than the rest of the file holds (corrupt or truncated)");
  return static_cast<std::uint64_t>(n);
}

void BodyReader::skip_row(const Element& element, const Place& where) {
  for (const Property& p : element.properties) {
    const std::uint64_t n = p.is_list ? next_count(p.count_type, p.type, where) : 1;
    if (format_ == Format::Ascii) {
      for (std::uint64_t i = 0; i < n; ++i) next(p.type, where);
      continue;
    }
    const std::uint64_t bytes = n * size_of(p.type);  // next_count bounded n by what remains
    if (remaining() < bytes) fail("the file ends inside " + where.str() + " (truncated)");
    at_ += bytes;
  }
}

double BodyReader::next_binary(Scalar type, const Place& where) {
  const std::size_t size = size_of(type);
  if (remaining() < size) fail("the file ends inside " + where.str() + " (truncated)");
  unsigned char raw[8];
  std::memcpy(raw, body_.data() + at_, size);
  at_ += size;
  const bool swap = (format_ == Format::BinaryBigEndian) == (std::endian::native == std::endian::little);
  if (swap) std::reverse(raw, raw + size);
  switch (type) {
    case Scalar::Int8: return static_cast<double>(static_cast<std::int8_t>(raw[0]));
    case Scalar::Uint8: return raw[0];
    case Scalar::Int16: return load<std::int16_t>(raw);
    case Scalar::Uint16: return load<std::uint16_t>(raw);
    case Scalar::Int32: return load<std::int32_t>(raw);
    case Scalar::Uint32: return load<std::uint32_t>(raw);
    case Scalar::Float32: return load<float>(raw);
    case Scalar::Float64: return load<double>(raw);
  }
  return 0;
}

std::string_view BodyReader::next_word(const Place& where) {
  while (at_ < body_.size() && is_space(body_[at_])) ++at_;
  const std::size_t start = at_;
  while (at_ < body_.size() && !is_space(body_[at_])) ++at_;
  if (start == at_) fail("the file ends inside " + where.str() + " (truncated)");
  return body_.substr(start, at_ - start);
}

}  // namespace touchcloud::ply
