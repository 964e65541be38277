#!/usr/bin/env bash
# Runs every libFuzzer target of a build folder configured with AVSM_BUILD_FUZZERS=ON
# (run_fuzz_smoke.sh or tools/test.sh --sanitize builds them):
#   1. writes the seed corpus (small valid files of every format);
#   2. replays the kept crash inputs of tests/scene/fuzz/regressions/<target>/ once each;
#   3. fuzzes each target for SECONDS (AddressSanitizer + UBSan);
#   4. prints one line per target: executions, coverage (cov: and ft: of libFuzzer's
#      last stats line), new corpus units and crashes.
# Any crash, leak, sanitizer report, timeout or exception other than LoadError fails
# it; libFuzzer leaves the input as crash-* / leak-* / timeout-* / oom-* in
# BUILD_DIR/fuzz-work/<target>/. With AVSM_FUZZ_KEEP_CRASHES=1 those inputs are also
# copied into regressions/<target>/, where every later run replays them.
#
#   tests/scene/fuzz/run_fuzzers.sh BUILD_DIR SECONDS
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../../.." && pwd)"
build="${1:?usage: run_fuzzers.sh BUILD_DIR SECONDS}"
seconds="${2:?usage: run_fuzzers.sh BUILD_DIR SECONDS}"
bin="$build/tests/scene/fuzz"
targets=(tfx cyhair gltf scene_json vdb_layout)

if [ ! -x "$bin/avsm_fuzz_make_seeds" ]; then
  echo "run_fuzzers: no fuzz targets in $build (configure it with -DAVSM_BUILD_FUZZERS=ON and build avsm_fuzz_all)"
  exit 1
fi
rm -rf "$build/fuzz-seeds"
"$bin/avsm_fuzz_make_seeds" "$build/fuzz-seeds" "$repo/content"

# The last value of a libFuzzer stats field ("cov: 396") in a log, or "-".
last_stat() { grep -oE "$1: *[0-9]+" "$2" | tail -1 | awk '{print $NF}' | grep . || echo -; }

status=0
table=()
for target in "${targets[@]}"; do
  work="$build/fuzz-work/$target"
  kept="$here/regressions/$target"
  mkdir -p "$work/corpus"
  rm -f "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-*
  mapfile -t regressions < <(find "$kept" -type f 2>/dev/null | sort)
  if [ ${#regressions[@]} -gt 0 ]; then
    echo "replaying ${#regressions[@]} kept input(s) of $target"
    if ! "$bin/avsm_fuzz_$target" -rss_limit_mb=2048 -timeout=10 "${regressions[@]}" > "$work/replay.txt" 2>&1; then
      echo "FAILED: $target crashes on a kept input again (log: $work/replay.txt)"; tail -40 "$work/replay.txt"; status=1
    fi
  fi
  echo "fuzzing $target for ${seconds}s"
  # The first folder collects new inputs; the seeds are read only. Crash artifacts
  # go to the work folder.
  if ! (cd "$work" && "$bin/avsm_fuzz_$target" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
        -max_len=16384 -print_final_stats=1 "$work/corpus" "$build/fuzz-seeds/$target" > "$work/log.txt" 2>&1); then
    echo "FAILED: $target (log: $work/log.txt)"; tail -40 "$work/log.txt"; status=1
  fi
  crashes=$(find "$work" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  if [ "$crashes" -gt 0 ] && [ "${AVSM_FUZZ_KEEP_CRASHES:-0}" = 1 ]; then
    mkdir -p "$kept"
    cp "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* "$kept"/ 2>/dev/null || true
    echo "kept $crashes input(s) of $target in $kept"
  fi
  table+=("$(printf '%-11s %12s %6s %6s %8s %8s' "$target" \
    "$(last_stat stat::number_of_executed_units "$work/log.txt")" "$(last_stat cov "$work/log.txt")" \
    "$(last_stat ft "$work/log.txt")" "$(last_stat stat::new_units_added "$work/log.txt")" "$crashes")")
done
printf '%-11s %12s %6s %6s %8s %8s\n' target executions cov ft new_units crashes
printf '%s\n' "${table[@]}"
exit $status
