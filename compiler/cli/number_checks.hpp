// Checks of numeric option values with messages a person can read: CLI11's PositiveNumber and NonNegativeNumber
// print their range as "0.000000 to 179769313486231570814527423731704356798070567525844996598917476803157260780..."
// (DBL_MAX written out, 309 digits).
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <string>

namespace mbgen::cli {

namespace detail {
inline CLI::Validator number_check(bool allow_zero) {
  return CLI::Validator(
      [allow_zero](std::string& text) -> std::string {
        const std::string wanted = allow_zero ? "a number of at least 0" : "a number greater than 0";
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return "expected " + wanted + ", not `" + text + "`";
        if (value < 0 || (!allow_zero && value == 0)) return "expected " + wanted + ", not " + text;
        return {};
      },
      allow_zero ? "NUMBER >= 0" : "NUMBER > 0");
}
}  // namespace detail

inline CLI::Validator positive_number() { return detail::number_check(false); }
inline CLI::Validator non_negative_number() { return detail::number_check(true); }

}  // namespace mbgen::cli
