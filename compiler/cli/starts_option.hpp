// The bound on the number of starts of a global search (--starts, --warm-starts; docs/limits.md). The fit holds
// every start's point and result at once, so a count in the billions filled the memory before the first local fit
// (`fit --starts 2000000000` took 9 GB within 20 s) instead of being refused; and CLI11's PositiveNumber said
// "Value 0 not in range 0.000000 to 1797693..." (309 digits) for `--starts 0`.
#pragma once

#include <CLI/CLI.hpp>

namespace mbgen::cli {

// 100 000 starts of even the smallest model take hours; their points and results some 100 MB.
inline constexpr int kMaxStarts = 100000;

inline CLI::Range starts_range() { return CLI::Range(1, kMaxStarts); }

}  // namespace mbgen::cli
