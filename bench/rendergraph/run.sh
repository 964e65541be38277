#!/usr/bin/env bash
# The frame graph's two tables: compile cost against pass count (up to 2,000
# passes), and the memory aliasing saves on the engine's real frame.
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build -j"$(nproc)" --target bench_rendergraph_compile avsm-capture > /dev/null
./build/bench/rendergraph/bench_rendergraph_compile
echo
python3 bench/rendergraph/frame_memory.py "$@"
