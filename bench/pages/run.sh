#!/usr/bin/env bash
# A paged light's page table on the CPU: milliseconds per frame at the default scene's
# size, for a still and an orbiting camera (bench/pages/page_table_cpu.cpp).
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build -j"$(nproc)" --target bench_page_table_cpu > /dev/null
./build/bench/pages/bench_page_table_cpu
