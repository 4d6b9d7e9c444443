#!/usr/bin/env bash
# The long fuzzing run (docs/limits.md, "Fuzzing"): builds the libFuzzer targets of tests/fuzz with clang, ASan and
# UBSan in build-fuzz/, then fuzzes each for SECONDS (default 600) on both cores, starting from the checked-in corpus.
# New inputs collect in build-fuzz/fuzz-corpus/TARGET; failures are written there as crash-*, timeout-*, oom-*.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
  -DMBGEN_SANITIZE=ON -DMBGEN_FUZZ=ON -DMBGEN_BUILD_BENCH=OFF -DMBGEN_WERROR=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target model_parser_fuzz data_csv_fuzz data_uff_fuzz data_uff55_fuzz
source=$PWD
# CLN's one-time start-up allocation is not a leak of ours (scripts/lsan.supp, as the ctest fuzz:TARGET runs use):
# without this, every model-parser job ended in a "leak" that wrote an empty crash-* input.
export LSAN_OPTIONS="suppressions=$source/scripts/lsan.supp:print_suppressions=0"
cd build-fuzz  # libFuzzer writes its job logs (fuzz-N.log) into the working directory
status=0
for target in model_parser data_csv data_uff data_uff55; do
  corpus=fuzz-corpus/$target
  mkdir -p "$corpus"
  echo "fuzz: $target for $seconds s"
  "tests/fuzz/${target}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
    -jobs="$(nproc)" -workers="$(nproc)" -artifact_prefix="$corpus/" "$corpus" "$source/tests/fuzz/corpus/$target" \
    > "fuzz-$target.log" 2>&1 || status=1
  ls "$corpus" | grep -E '^(crash|timeout|oom|leak)-' || true
done
exit $status
