#!/usr/bin/env bash
# Light in media: the targets that are built so far.
#  - Smoke lit as a medium (multiple scattering and sky light) against a CPU path tracer, on
#    the real-asset scene (when ../shared/content is there) and the default scene (smoke.py).
#  - Fog through the froxel grid against its per-pixel march, at 1280x720, on the default
#    scene under a ground fog and on content/examples/fog.scene.json (fog.py).
#  - A rect light's cost against a hard spot light at its centre, on the softbox example
#    (area.py; needs ../shared/content), and the window example's fog against its per-pixel march
#    at K = 16, 64 and 256 (fog.py --virtual-lights).
# Extra arguments go to smoke.py (e.g. --width 640 --height 360 --paths 128).
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build -j"$(nproc)" --target avsm-capture avsm_default_content > /dev/null
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
scenes=()
if [ -f ../shared/content/smoke1/smoke.vdb ]; then scenes+=(content/real_assets.scene.json); else
  echo "(real-asset scene skipped: ../shared/content is missing)"; fi
scenes+=(build/content/default/scene.json)
for scene in "${scenes[@]}"; do
  python3 bench/media/smoke.py --scene "$scene" "$@"
  echo
done
fog_scenes=(build/content/default/scene.json)
if [ -f ../shared/content/smoke1/smoke.vdb ]; then fog_scenes+=(content/examples/fog.scene.json); fi
for scene in "${fog_scenes[@]}"; do
  python3 bench/media/fog.py --scene "$scene"
  echo
done
if [ -f ../shared/content/sintel/sintel_head.glb ]; then
  python3 bench/media/area.py --scene content/examples/softbox.scene.json
fi
# The window's rect light through smoke into fog, at K = 16, 64 and 256 virtual lights, small: the
# per-pixel reference looks every virtual light up at each of its 256 steps.
if [ -f ../shared/content/smoke1/smoke.vdb ]; then
  for k in 16 64 256; do
    python3 bench/media/fog.py --scene content/examples/window.scene.json --width 160 --height 90 --frames 1 \
      --virtual-lights "$k"
    echo
  done
fi
