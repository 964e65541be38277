#!/usr/bin/env bash
# The shadowed-lights tables (bench/avsm/lights.py): clustered against single maps on the
# sparse scene, the cost per light on the many-lights scene, and a point light's cube
# against a spot light, each measured in one run. Extra arguments go to lights.py
# (e.g. --width 1280 --height 720 --rounds 3).
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build -j"$(nproc)" --target avsm-capture avsm_default_content > /dev/null
python3 bench/avsm/lights.py "$@"
