// Checks of a YAML document that yaml-cpp does not make, and messages for
// what it throws. Private to the core.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "touchcloud/error.hpp"

namespace touchcloud {

// Why `file` cannot be read as a document: missing, a folder, a FIFO or a
// device (which would block or fail mid-read); nullopt for a regular file.
std::optional<std::string> not_a_regular_file(const std::filesystem::path& file);

// What yaml-cpp's exception means, in words ("bad file" is its depth limit).
std::string yaml_error_text(const YAML::Exception& e);

// Adds a diagnostic for every key that appears twice in one mapping, at the
// second with the first's position (yaml-cpp keeps both; lookups see one).
void check_duplicate_keys(const YAML::Node& root, const std::filesystem::path& file,
                          std::vector<Diagnostic>& diagnostics);

// `text` as a message may quote it: at most 40 characters, control
// characters escaped.
std::string quoted_excerpt(const std::string& text);

}  // namespace touchcloud
