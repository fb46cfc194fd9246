// The readers under test take paths: each input goes to one file per
// process (named by pid and extension), rewritten for every input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace touchcloud::fuzz {

const std::filesystem::path& input_file(const uint8_t* data, std::size_t size, const char* extension);

}  // namespace touchcloud::fuzz
