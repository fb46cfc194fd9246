#include "seed_option.hpp"

#include <charconv>
#include <cstdint>

namespace touchcloud::cli {

CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t v = 0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
        if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size())
          return "'" + text.substr(0, 40) + "' is not a seed: a whole number from 0 to 18446744073709551615";
        return {};
      },
      "UINT64");
}

}  // namespace touchcloud::cli
