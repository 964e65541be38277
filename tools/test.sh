#!/usr/bin/env bash
# The whole test suite: install what is missing, build, run everything through CTest.
# GPU tests run under Vulkan validation with synchronization validation.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
# One test per core; the tests that compare measured times are RUN_SERIAL in their
# CMakeLists, and the ones that start a virtual display take turns (RESOURCE_LOCK xvfb).
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
