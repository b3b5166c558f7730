#!/usr/bin/env bash
# The bench on a real Slurm: a single-node cluster from Debian's packages (munge, slurmctld, slurmd, with a
# slurm.conf generated in a temporary folder; no system file is read or changed, every daemon listens on
# its own socket or port and is stopped at the end), then
#   1. scripts/slurm/submit.sh runs a small config as a 3-task array and the merge after it; the merged
#      results.json holds the same records as a one-machine run of the config (every field but timings,
#      host and time of day) and report.html opens in headless Chromium (tests/app/report_browser.mjs);
#   2. an array cancelled half-way and submitted again completes, skipping the tasks it had recorded, with
#      one record per task and one row per render.
# Run by .ci/run after ./test.sh (it needs root for slurmd and the packages of scripts/install-deps.sh).
#   scripts/slurm/local-slurm-test.sh [build/app/bounce]
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=$(realpath "${1:-build/app/bounce}")
for tool in munged slurmctld slurmd sbatch squeue scancel python3; do
  command -v "$tool" >/dev/null || { echo "local-slurm-test: $tool is not installed (scripts/install-deps.sh)" >&2; exit 1; }
done
[[ $(id -u) == 0 ]] || { echo "local-slurm-test: slurmd runs jobs as their user: run as root" >&2; exit 1; }

tmp=$(mktemp -d /tmp/bounce-slurm.XXXXXX)
chmod 700 "$tmp"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  if [[ -f $tmp/munged.pid ]]; then kill "$(cat "$tmp/munged.pid")" 2>/dev/null || true; fi
  sleep 1
  [[ ${KEEP:-0} == 1 ]] || rm -rf "$tmp"
}
trap cleanup EXIT
fail() {
  echo "local-slurm-test: FAILED: $*" >&2
  for log in "$tmp"/*.log; do echo "--- $log" >&2; tail -20 "$log" >&2; done
  exit 1
}

# munge: a fresh key, its own socket.
dd if=/dev/urandom of="$tmp/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge.key"
munged --force --key-file="$tmp/munge.key" --socket="$tmp/munge.sock" --pid-file="$tmp/munged.pid" \
  --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed"

# slurm.conf: this machine as the one node (slurmd -C gives its CPUs and memory), ports of our own.
node=$(hostname -s)
mkdir -p "$tmp/state" "$tmp/spool"
cat >"$tmp/slurm.conf" <<EOF
ClusterName=bounce-test
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$((17000 + RANDOM % 1000))
SlurmdPort=$((18000 + RANDOM % 1000))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge.sock
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
$(slurmd -C | head -1) NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >"$tmp/slurmctld.out.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" >"$tmp/slurmd.out.log" 2>&1 &
pids+=($!)
for _ in $(seq 60); do
  sinfo -h -o %T 2>/dev/null | grep -qx idle && break
  sleep 0.5
done
sinfo -h -o %T 2>/dev/null | grep -qx idle || fail "the node did not come up"
echo "local-slurm-test: slurm up ($node, $(sinfo -h -o %c) CPUs)"

# Two renders, a sweep and the path tracer on one scene at 16x16: 7 tasks, a second or less each.
cat >"$tmp/tiny.json" <<'EOF'
{"size": "16x16", "warmup": 0, "frames": 1, "reference": {"spp": 16}, "scenes": ["cornell-spot"],
 "pathTracerSpp": [4], "runs": [{"technique": "direct"}, {"technique": "rsm", "sweep": {"vpls": [4, 16]}}]}
EOF
# The one to cancel part way: more tasks per shard (17 in all), so that shards running side by side on a
# machine of many cores are still at work when the first record appears.
cat >"$tmp/longer.json" <<'EOF'
{"size": "16x16", "warmup": 0, "frames": 1, "reference": {"spp": 16}, "scenes": ["cornell-spot"],
 "pathTracerSpp": [4, 16, 64], "runs": [{"technique": "direct"},
 {"technique": "rsm", "sweep": {"vpls": [4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048]}}]}
EOF
args=(--backend osmesa --cache "$tmp/cache")
for c in tiny longer; do
  "$bin" bench --config "$tmp/$c.json" --out "$tmp/whole-$c" "${args[@]}" >"$tmp/whole-$c.log" 2>&1 ||
    fail "the one-machine run of $c.json"
done

# Waits for a job to leave the queue (at most $2 seconds).
wait_job() {
  for _ in $(seq $((2 * $2))); do
    [[ -z $(squeue -h -j "$1" 2>/dev/null) ]] && return 0
    sleep 0.5
  done
  fail "job $1 still queued after $2 s"
}
merge_id() { sed -n 's/^merge job \([0-9]*\).*/\1/p' <<<"$1"; }
array_id() { sed -n 's/^array job \([0-9]*\).*/\1/p' <<<"$1"; }

# The records of two results.json files, all but timings, host and time of day, must be the same.
same_records() {
  python3 - "$1" "$2" <<'EOF'
import json, sys
def strip(j):
    if isinstance(j, list):
        return [strip(x) for x in j]
    if isinstance(j, dict):
        return {k: strip(v) for k, v in j.items()
                if not k.endswith("Ms") and k not in ("host", "time", "pareto", "passes")}
    return j
a, b = (json.load(open(p)) for p in sys.argv[1:3])
if len(a) != len(b):
    sys.exit("%d rows against %d" % (len(a), len(b)))
for i, (x, y) in enumerate(zip(a, b)):
    if strip(x) != strip(y):
        sys.exit("row %d differs: %s" % (i, [k for k in set(strip(x)) | set(strip(y)) if strip(x).get(k) != strip(y).get(k)]))
print("local-slurm-test: %d rows, the same records" % len(a))
EOF
}

# 1. Three shards and the merge.
start=$(date +%s)
tasks=$("$bin" bench --config "$tmp/tiny.json" --list-tasks | wc -l)
out=$(scripts/slurm/submit.sh "$tmp/tiny.json" 3 "$tmp/run" "${args[@]}") || fail "submit.sh: $out"
echo "$out"
wait_job "$(merge_id "$out")" 120
echo "local-slurm-test: array and merge done in $(($(date +%s) - start)) s"
grep -q "merged $tasks of $tasks tasks" "$tmp"/run/logs/merge-*.log || fail "the merge: $(cat "$tmp"/run/logs/merge-*.log)"
same_records "$tmp/whole-tiny/results.json" "$tmp/run/results.json" || fail "merged records differ from one machine's"
if command -v node >/dev/null && [[ -d node_modules/playwright-core ]]; then
  node tests/app/report_browser.mjs "$tmp/run" || fail "report.html in headless Chromium"
  echo "local-slurm-test: report.html opens in headless Chromium"
else
  fail "node and playwright-core are needed for the page's check (scripts/install-deps.sh, npm ci)"
fi

# 2. Cancelled half-way (as soon as a task is recorded), then submitted again.
tasks=$("$bin" bench --config "$tmp/longer.json" --list-tasks | wc -l)
out=$(scripts/slurm/submit.sh "$tmp/longer.json" 3 "$tmp/resume" "${args[@]}") || fail "submit.sh: $out"
for _ in $(seq 400); do
  compgen -G "$tmp/resume/tasks/*.json" >/dev/null && break
  sleep 0.05
done
scancel "$(array_id "$out")"
wait_job "$(merge_id "$out")" 60
before=$(find "$tmp/resume/tasks" -name '*.json' | wc -l)
((before < tasks)) || fail "the array had finished before it was cancelled: resuming was not tested"
grep -q "missing task" "$tmp"/resume/logs/merge-*.log || fail "the merge of a cancelled array names no missing task"
stamps=$(cd "$tmp/resume/tasks" && stat -c '%n %Y.%y' -- *.json)
out=$(scripts/slurm/submit.sh "$tmp/longer.json" 3 "$tmp/resume" "${args[@]}") || fail "submit.sh again: $out"
wait_job "$(merge_id "$out")" 120
after=$(find "$tmp/resume/tasks" -name '*.json' | wc -l)
[[ $after == "$tasks" ]] || fail "$after records for $tasks tasks after the resubmission"
while read -r name stamp; do
  [[ $(cd "$tmp/resume/tasks" && stat -c '%Y.%y' -- "$name") == "$stamp" ]] || fail "$name was run again"
done <<<"$stamps"
grep -q "merged $tasks of $tasks tasks" "$tmp/resume/logs/merge-$(merge_id "$out").log" || fail "the second merge"
same_records "$tmp/whole-longer/results.json" "$tmp/resume/results.json" || fail "resumed records differ"
echo "local-slurm-test: cancelled with $before of $tasks tasks recorded; resubmitted, $after records, none run twice"
echo "local-slurm-test: passed in $(($(date +%s) - start)) s"
