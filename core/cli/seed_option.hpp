// The check every --seed option shares: a whole number from 0 to 2^64-1.
// CLI11 reads "-1" and "99999999999999999999" as 2^64-1 (strtoull); a seed
// that is not the one given would make a run that cannot be repeated.
#pragma once

#include <CLI/CLI.hpp>

namespace touchcloud::cli {

CLI::Validator seed_value();

}  // namespace touchcloud::cli
