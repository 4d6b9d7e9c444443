// The seed of a random search (--seed; docs/cli.md): a decimal integer from 0 to 2^64 - 1. CLI11's conversion to an
// unsigned type took `-1` (as 2^64 - 1) and wrapped values beyond the range, so two different texts ran the same
// search without a word; the seed used is recorded in the results' JSON.
#pragma once

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdlib>
#include <string>

namespace mbgen::cli {

inline CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.size() <= 20 && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits) return "a seed is a whole number from 0 to 18446744073709551615, not `" + text + "`";
        errno = 0;
        (void)std::strtoull(text.c_str(), nullptr, 10);
        if (errno == ERANGE) return "a seed is at most 18446744073709551615 (2^64 - 1), not " + text;
        return {};
      },
      "SEED");
}

}  // namespace mbgen::cli
