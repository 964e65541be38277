#!/usr/bin/env bash
# The engine on a GPU in one unattended run of at most 5 minutes (--budget): the device
# and its limits, the GPU tests under validation, captures of the default and the
# real-asset scene at 1920x1080 with per-pass timings, and the techniques bench at 256^2;
# one table (summary.txt / summary.json) in the output folder. --smoke: every step, tiny,
# for CI on lavapipe. The steps live in bench/gpu/check.py; --help says everything.
# Needs bash, coreutils, python3 (standard library) and the project's build outputs.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
if ! command -v python3 > /dev/null; then
  echo "bench/gpu/check.sh: python3 is needed" >&2
  exit 2
fi
exec python3 "$here/check.py" "$@"
