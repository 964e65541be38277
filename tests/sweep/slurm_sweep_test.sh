#!/usr/bin/env bash
# A sweep through a real Slurm: starts a single-node cluster on this machine
# (slurm_local_cluster.sh), submits MANIFEST with `avsm-sweep slurm`, waits, and
# checks every job's result and that index.json equals LOCAL_DIR's, the same manifest
# run locally (`avsm-sweep run`), apart from wall_s. Then: sbatch refusing a setting is
# a clear error naming it, and tasks Slurm cancels before they run are failed jobs
# naming their Slurm state. The daemons are stopped at the end, pass or fail.
#
#   slurm_sweep_test.sh AVSM_SWEEP MANIFEST LOCAL_DIR WORK
#
# Exit status 77 (SKIPPED in CTest): Slurm/munge not installed or the daemons would
# not start here.
set -euo pipefail

[ $# -eq 4 ] || { echo "usage: $0 AVSM_SWEEP MANIFEST LOCAL_DIR WORK" >&2; exit 2; }
sweep=$1
manifest=$2
local_dir=$3
work=$4
[ -f "$local_dir/index.json" ] || { echo "$local_dir/index.json: missing (run the sweep locally first)" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
SKIP=77

step() { echo "== $*"; }
fail() {
  echo "FAILED: $*" >&2
  exit 1
}

# Short on purpose: Unix socket paths under it are limited to 107 bytes.
cluster=$(mktemp -d /tmp/avsm-slurm.XXXXXX)
finish() {
  local status=$?
  if [ $status -ne 0 ] && [ $status -ne $SKIP ]; then
    for log in "$cluster"/log/slurmctld.log "$cluster"/log/slurmd.log "$work"/*/slurm/task-*.log; do
      [ -f "$log" ] || continue
      echo "---- $log (last lines)" >&2
      tail -n 15 "$log" >&2
    done
  fi
  "$here/slurm_local_cluster.sh" stop "$cluster"
  rm -rf "$cluster"
  exit $status
}
trap finish EXIT

step "start the local Slurm cluster in $cluster"
"$here/slurm_local_cluster.sh" start "$cluster"  # 77 here skips the test
export SLURM_CONF=$cluster/slurm.conf
rm -rf "$work"
mkdir -p "$work"

step "submit $manifest to Slurm and wait"
"$sweep" slurm "$manifest" --out "$work/slurm"
expected_exit=0  # wait and status: 0 every job done, 1 some failed (as in the local run)
if grep -q '"status": "failed"' "$local_dir/index.json"; then expected_exit=1; fi
status=0
"$sweep" wait "$work/slurm" --timeout 300 || status=$?
[ $status -eq $expected_exit ] || fail "avsm-sweep wait exited $status, expected $expected_exit"
cmake -DA="$work/slurm" -DB="$local_dir" -P "$here/check_same_sweep.cmake"
jobs=$(grep -c '"capture_args":' "$work/slurm/index.json")  # one per job (shots have ids too)
for ((task = 0; task < jobs; ++task)); do
  [ -s "$work/slurm/slurm/task-$task.log" ] || fail "Slurm wrote no $work/slurm/slurm/task-$task.log"
done

step "sbatch refusing a setting is a clear error naming it"
if "$sweep" slurm "$manifest" --out "$work/refused" --partition no_such_partition 2> "$work/refused.err"; then
  fail "avsm-sweep slurm --partition no_such_partition succeeded"
fi
cat "$work/refused.err"
grep -q "invalid partition specified: no_such_partition" "$work/refused.err" || fail "Slurm's message is not quoted"
grep -q "change --partition" "$work/refused.err" || fail "the setting to change is not named"

step "tasks cancelled before they ran are failed jobs, naming their Slurm state"
"$sweep" slurm "$manifest" --out "$work/cancelled" --sbatch-arg --begin=now+1hour
job_id=$(sed -n 's/.*"job_id": *"\([0-9]*\)".*/\1/p' "$work/cancelled/slurm/slurm.json")
[ -n "$job_id" ] || fail "no job id in $work/cancelled/slurm/slurm.json"
scancel "$job_id"
status=0
"$sweep" wait "$work/cancelled" --timeout 60 || status=$?
[ $status -eq 1 ] || fail "avsm-sweep wait on a cancelled sweep exited $status, expected 1 (some jobs failed)"
cancelled=$(grep -c "Slurm array task ${job_id}_[0-9]* ended (CANCELLED)" "$work/cancelled/index.json" || true)
[ "$cancelled" -eq "$jobs" ] || fail "$cancelled of $jobs jobs in $work/cancelled/index.json name their cancelled task"
step "passed"
