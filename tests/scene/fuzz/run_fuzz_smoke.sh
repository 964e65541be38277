#!/usr/bin/env bash
# Fuzz smoke test of the scene loaders: configures a clang build of this
# project with AVSM_BUILD_FUZZERS=ON in its own folder, builds only the fuzz
# targets, then runs each libFuzzer target for a few seconds (AddressSanitizer +
# UBSan) through run_fuzzers.sh, which also replays the kept crash inputs of
# regressions/ and says what fails a run.
#
#   tests/scene/fuzz/run_fuzz_smoke.sh [BUILD_DIR]   (default: build-fuzz)
#   AVSM_FUZZ_SECONDS=60 for longer runs per target (default 10);
#   bench/fuzz/run.sh MINUTES for long runs.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../../.." && pwd)"
build="${1:-$repo/build-fuzz}"
seconds="${AVSM_FUZZ_SECONDS:-10}"
jobs="${AVSM_FUZZ_JOBS:-2}"

mkdir -p "$build"
cmake -S "$repo" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAVSM_BUILD_FUZZERS=ON -DAVSM_BUILD_BENCH=OFF > "$build/configure.log" 2>&1 \
  || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j"$jobs" --target avsm_fuzz_all > "$build/build.log" 2>&1 \
  || { tail -50 "$build/build.log"; exit 1; }
exec "$here/run_fuzzers.sh" "$build" "$seconds"
