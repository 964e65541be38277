#!/usr/bin/env bash
# Long fuzzing of the scene loaders: every libFuzzer target for MINUTES each, then a
# table of executions, coverage (cov:/ft: of libFuzzer's last stats line), new corpus
# units and crashes per target. A crash's input is kept under
# tests/scene/fuzz/regressions/<target>/, which the CI's fuzz run replays; fix the
# loader, then commit the input as its regression test.
#
#   bench/fuzz/run.sh MINUTES [BUILD_DIR]   (default build folder: build-fuzz)
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
minutes="${1:?usage: bench/fuzz/run.sh MINUTES [BUILD_DIR]}"
if ! [[ "$minutes" =~ ^[1-9][0-9]*$ ]]; then
  echo "bench/fuzz/run.sh: MINUTES expects a positive whole number, got '$minutes'"; exit 2
fi
AVSM_FUZZ_SECONDS=$((minutes * 60)) AVSM_FUZZ_KEEP_CRASHES=1 \
  exec "$repo/tests/scene/fuzz/run_fuzz_smoke.sh" "${2:-$repo/build-fuzz}"
