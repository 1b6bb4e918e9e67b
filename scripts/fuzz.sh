#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) with clang-14 + ASan + UBSan and runs each for a bounded time on a
# copy of its seed corpus (fuzz/corpus/<harness>/; the repository's corpus is never modified).
#   scripts/fuzz.sh [SECONDS_PER_HARNESS (default 60)] [HARNESS...]
# Exits non-zero on the first finding; the crashing input is saved as build-fuzz/findings/<harness>/crash-*.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
harnesses=("$@")
# dlc_h5 is run on request only: mutated HDF5 bytes crash libhdf5 1.10 itself (docs/formats.md, "Fuzzing").
[ ${#harnesses[@]} -eq 0 ] && harnesses=(case_json trial_csv array_config pickled_value janelia)

CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIBRISSA_WERROR=ON \
  -DVIBRISSA_FUZZ=ON -DVIBRISSA_BUILD_TESTS=OFF -DVIBRISSA_BUILD_BENCHMARKS=OFF -DVIBRISSA_BUILD_PYTHON=OFF > /dev/null
cmake --build build-fuzz -j2 --target "${harnesses[@]/%/_fuzzer}"

for h in "${harnesses[@]}"; do
  work="build-fuzz/corpus/$h"
  findings="build-fuzz/findings/$h"
  rm -rf "$work"
  mkdir -p "$work" "$findings"
  cp fuzz/corpus/"$h"/* "$work"/
  echo "=== fuzz $h: ${seconds} s ==="
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "build-fuzz/fuzz/${h}_fuzzer" "$work" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -artifact_prefix="$findings/" -print_final_stats=1 2>&1 | tail -n 12
  [ "${PIPESTATUS[0]}" -eq 0 ] || { echo "fuzz $h: finding saved in $findings" >&2; exit 1; }
done
