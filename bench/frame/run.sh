#!/usr/bin/env bash
# The camera side of the frame, fast against reference volume shading: per scene,
# the per-pass GPU ms of both paths measured in one avsm-capture run (interleaved
# frames, --compare-volume-shading), their ratios, the issue's targets, and the
# smoke-pixel quality of the fast path against the reference. Scenes: the default,
# the real-asset scene (when ../shared/content is there) and both benchmark scenes.
# Extra arguments go to frame.py (e.g. --width 640 --height 360 --frames 3, or
# --capture-arg=--volume-step=2).
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build -j"$(nproc)" --target avsm-capture avsm_default_content > /dev/null
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
content=build/content/default
scenes=("$content/scene.json")
if [ -f ../shared/content/smoke1/smoke.vdb ]; then scenes+=(content/real_assets.scene.json); else
  echo "(real-asset scene skipped: ../shared/content is missing)"; fi
scenes+=("$content/bench_smoke_columns.scene.json" "$content/bench_smoke_hair.scene.json")
for scene in "${scenes[@]}"; do
  python3 bench/frame/frame.py --scene "$scene" "$@"
  echo
done
