#!/usr/bin/env bash
# The AVSM technique table on the default scene and the two benchmark scenes
# (three smoke columns; smoke and hair over an opaque receiver), each measured
# in one run. Extra arguments go to techniques.py (e.g. --width 640 --height 360).
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build -j"$(nproc)" --target avsm-capture avsm_default_content > /dev/null
content=build/content/default
for scene in "$content/scene.json" "$content/bench_smoke_columns.scene.json" "$content/bench_smoke_hair.scene.json"; do
  python3 bench/avsm/techniques.py --scene "$scene" "$@"
  echo
done
