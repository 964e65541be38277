#!/usr/bin/env bash
# The viewer soak (bench/soak/soak.py): FRAMES frames (a multiple of 50, at least 250) of
# avsm-viewer --control --validation at 96x54 with every kind of edit, on copies of the
# shaders and the default scene in build/soak/. Prints resident memory and the heap in use
# at frames 100, 250, 1000, 5000, 10000 and the last, the validation message count and
# frame-time percentiles; exits 1 saying why when memory grows more than 2% after frame
# 250 (the warm-up: every technique's pipelines compiled once), validation reports
# anything, a frame hangs or an edit is not followed. Extra arguments go to soak.py;
# --no-validation measures the engine's memory without the validation layer's.
#
#   bench/soak/run.sh FRAMES [soak.py options]      e.g. bench/soak/run.sh 10000
set -euo pipefail
cd "$(dirname "$0")/../.."
frames="${1:?usage: bench/soak/run.sh FRAMES [soak.py options]}"
shift
cmake --build build -j"$(nproc)" --target avsm-viewer avsm_default_content > /dev/null
exec python3 bench/soak/soak.py build/tools/avsm-viewer shaders build/content/default --frames "$frames" \
  --work build/soak "$@"
