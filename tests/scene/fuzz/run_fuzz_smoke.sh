#!/usr/bin/env bash
# Fuzz smoke test of the scene loaders: configures a clang build of this
# project with AVSM_BUILD_FUZZERS=ON in its own folder, builds only the fuzz
# targets, writes a seed corpus, then runs each libFuzzer target for a few
# seconds (AddressSanitizer + UBSan). Any crash, leak, sanitizer report or
# exception other than LoadError fails it; libFuzzer leaves the input as
# crash-* / leak-* / timeout-* in the build folder's fuzz-work/.
#
#   tests/scene/fuzz/run_fuzz_smoke.sh [BUILD_DIR]   (default: build-fuzz)
#   AVSM_FUZZ_SECONDS=60 for longer runs per target (default 10).
set -euo pipefail
repo="$(cd "$(dirname "$0")/../../.." && pwd)"
build="${1:-$repo/build-fuzz}"
seconds="${AVSM_FUZZ_SECONDS:-10}"
jobs="${AVSM_FUZZ_JOBS:-2}"

mkdir -p "$build"
cmake -S "$repo" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAVSM_BUILD_FUZZERS=ON -DAVSM_BUILD_BENCH=OFF > "$build/configure.log" 2>&1 \
  || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j"$jobs" --target avsm_fuzz_all > "$build/build.log" 2>&1 \
  || { tail -50 "$build/build.log"; exit 1; }

bin="$build/tests/scene/fuzz"
rm -rf "$build/fuzz-seeds"
"$bin/avsm_fuzz_make_seeds" "$build/fuzz-seeds" "$repo/content"
status=0
for target in tfx cyhair gltf scene_json vdb_layout; do
  work="$build/fuzz-work/$target"
  mkdir -p "$work/corpus"
  echo "fuzzing $target for ${seconds}s"
  # The first folder collects new inputs; the seeds are read only. Crash
  # artifacts go to the work folder.
  if ! (cd "$work" && "$bin/avsm_fuzz_$target" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
        -max_len=16384 -print_final_stats=1 "$work/corpus" "$build/fuzz-seeds/$target" > "$work/log.txt" 2>&1); then
    echo "FAILED: $target (log: $work/log.txt)"; tail -40 "$work/log.txt"; status=1
  else
    grep -E "stat::number_of_executed_units|stat::new_units_added" "$work/log.txt" | tr '\n' ' '; echo
  fi
done
exit $status
