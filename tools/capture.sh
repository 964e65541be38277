#!/usr/bin/env bash
# The main job: install what is missing, build (Release), capture the default scene.
# Extra arguments go to avsm-capture (see: build/tools/avsm-capture --help).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
# Ninja for a new build folder; one configured before keeps its generator.
generator=""
[ -f build/CMakeCache.txt ] || generator="-GNinja"
cmake -S . -B build $generator -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
build/tools/avsm-capture --out out/capture "$@"
