#!/usr/bin/env bash
# The test suite: install what is missing, build, run the tests through CTest.
# GPU tests run under Vulkan validation with synchronization validation.
#
#   tools/test.sh [CTEST ARGS]             every test, built in build/
#   tools/test.sh --sanitize [CTEST ARGS]  AddressSanitizer + UBSan, built with clang in
#       build-asan/: the loaders, the frame-graph planner, the AVSM core, one small capture
#       of the default scene and a short run of the loaders' fuzz targets (ctest labels
#       scene and sanitize); only their targets are built. Any sanitizer report fails.
#
# Tests run in parallel, one per core; the few that compare measured times are
# RUN_SERIAL in their CMakeLists.
set -euo pipefail
cd "$(dirname "$0")/.."
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
jobs="$(nproc)"

# Ninja for a new build folder (it schedules the whole tree's compiles across the cores);
# a folder configured before keeps the generator it was made with.
generator() {
  [ -f "$1/CMakeCache.txt" ] || echo "-GNinja"
}

run_suite() {
  cmake -S . -B build $(generator build) -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build build -j"$jobs"
  ctest --test-dir build --output-on-failure -j"$jobs" "$@"
}

run_sanitized_subset() {
  # vptr is off: Debian's glslang is built without RTTI. Leak checks are off (Vulkan
  # drivers and layers keep allocations until exit). Every other report stops the
  # process with a failing exit status.
  # System headers are left out of UBSan only (cmake/ubsan_ignorelist.txt says why).
  local sanitizers="-fsanitize=address,undefined -fno-sanitize=vptr -fno-sanitize-recover=all"
  local flags="$sanitizers -fno-omit-frame-pointer -fsanitize-ignorelist=$PWD/cmake/ubsan_ignorelist.txt"
  export ASAN_OPTIONS="detect_leaks=0:halt_on_error=1"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
  # -O0: half the compile time of -O1 (measured on engine/scene/gltf.cpp: 10.6 against
  # 21.9 CPU seconds), and these tests spend their time in the driver, not in our code.
  # Line tables only: file:line in the reports, for little compile time.
  cmake -S . -B build-asan $(generator build-asan) -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG="-O0 -gline-tables-only" -DCMAKE_CXX_FLAGS_DEBUG="-O0 -gline-tables-only" \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" -DCMAKE_SHARED_LINKER_FLAGS="$sanitizers" \
    -DAVSM_BUILD_FUZZERS=ON -DAVSM_BUILD_BENCH=OFF -DAVSM_BUILD_VIEWER=OFF > /dev/null
  cmake --build build-asan -j"$jobs" \
    --target avsm_scene_tests rendergraph_tests avsm_core_tests avsm-capture avsm_fuzz_all
  ctest --test-dir build-asan --output-on-failure -j"$jobs" -L '^(scene|sanitize)$' "$@"
}

sanitize=0
if [ "${1:-}" = "--sanitize" ]; then
  sanitize=1
  shift
fi
tools/install-deps.sh
if [ "$sanitize" = 1 ]; then
  run_sanitized_subset "$@"
else
  run_suite "$@"
fi
