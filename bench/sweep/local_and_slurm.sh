#!/usr/bin/env bash
# Issue 18's "done when" as one run: a sweep manifest (default: techniques.json, the
# default and real-asset scenes over AVSM-4/8/16, OSM-32 and uncompressed at 1280x720)
# run locally and through a single-node Slurm cluster on this machine, then
#   - the two index.json compared apart from wall_s (tests/sweep/check_same_sweep.cmake),
#   - the local sweep's report opened in headless Chromium and checked for every job
#     (tests/cmake/check_sweep_report.cmake),
#   - a table of the jobs: status, wall seconds locally and on Slurm.
#
#   bench/sweep/local_and_slurm.sh [--build DIR] [--jobs N] [MANIFEST] [OUT]
#
# OUT defaults to /tmp/avsm-sweep-bench; it holds OUT/local, OUT/slurm and the report.
# The cluster is the tests' own (tests/sweep/slurm_local_cluster.sh), started and
# stopped here; it runs one task at a time per core, as the local run's --jobs does.
# The real-asset scene needs ../shared/content (content/README.md).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$root/build
jobs=1
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    -*) echo "unknown option $1 (see the usage at the top of $0)" >&2; exit 2 ;;
    *) break ;;
  esac
done
manifest=$(realpath "${1:-$here/techniques.json}")
out=${2:-/tmp/avsm-sweep-bench}
sweep=$build/tools/avsm-sweep
[ -x "$sweep" ] || { echo "$sweep: not built (cmake --build $build --target avsm-sweep avsm-capture)" >&2; exit 2; }
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
mkdir -p "$out"
out=$(cd "$out" && pwd)

step() { echo "== $(date +%T) $*"; }

step "local: avsm-sweep run $manifest --jobs $jobs"
local_status=0
"$sweep" run "$manifest" --out "$out/local" --jobs "$jobs" --force || local_status=$?
[ $local_status -le 1 ] || { echo "avsm-sweep run exited $local_status" >&2; exit 1; }

cluster=$(mktemp -d /tmp/avsm-slurm.XXXXXX)  # short: socket paths under it are limited
stop_cluster() { "$root/tests/sweep/slurm_local_cluster.sh" stop "$cluster"; rm -rf "$cluster"; }
trap stop_cluster EXIT
step "start the local Slurm cluster in $cluster"
"$root/tests/sweep/slurm_local_cluster.sh" start "$cluster"
export SLURM_CONF=$cluster/slurm.conf
rm -rf "$out/slurm"
step "slurm: avsm-sweep slurm $manifest"
"$sweep" slurm "$manifest" --out "$out/slurm"
slurm_status=0
"$sweep" wait "$out/slurm" || slurm_status=$?
[ $slurm_status -eq $local_status ] || { echo "Slurm's sweep exited $slurm_status, the local one $local_status" >&2; exit 1; }

step "index.json through Slurm against the local one, apart from wall_s"
cmake -DA="$out/slurm" -DB="$out/local" -P "$root/tests/sweep/check_same_sweep.cmake"
echo "same jobs, statuses, settings, outputs and errors"

step "report of the local sweep, opened in headless Chromium"
"$sweep" report "$out/local"
cmake -DDIR="$out/local" -P "$root/tests/cmake/check_sweep_report.cmake"
echo "report: $out/local/report.html"

step "jobs"
python3 - "$out/local/index.json" "$out/slurm/index.json" <<'EOF'
import json, sys
local, slurm = (json.load(open(p))["jobs"] for p in sys.argv[1:3])
wall = {j["id"]: j.get("wall_s") for j in slurm}
print(f"| {'job':<24} | {'status':<6} | {'local s':>8} | {'slurm s':>8} |")
print(f"|{'-' * 26}|{'-' * 8}|{'-' * 10}|{'-' * 10}|")
for j in local:
    fmt = lambda s: f"{s:8.1f}" if isinstance(s, (int, float)) else f"{'-':>8}"
    print(f"| {j['id']:<24} | {j['status']:<6} | {fmt(j.get('wall_s'))} | {fmt(wall.get(j['id']))} |")
EOF
