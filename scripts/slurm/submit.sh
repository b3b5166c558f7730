#!/usr/bin/env bash
# Submits a bench config as a Slurm job array of N shards (scripts/slurm/study.sbatch) and the merge that
# writes DIR/report.html and the rest once every shard has ended, failed or not (afterany: the merge then
# names the tasks that have no record and exits 1). Prints both job ids.
#
#   scripts/slurm/submit.sh CONFIG N DIR [bench options...]
#   scripts/slurm/submit.sh bench/study.json 16 /shared/study --full --cache /shared/bounce-cache
#
# DIR must be on storage every node sees; the shards' logs go to DIR/logs/. BOUNCE_BIN names another
# bounce than this tree's build/app/bounce; SBATCH_* variables and sbatch's own options (e.g.
# SBATCH_PARTITION) apply as usual.
set -euo pipefail
if [[ $# -lt 3 ]]; then
  echo "usage: $0 CONFIG N DIR [bench options...]" >&2
  exit 2
fi
config=$1 shards=$2 dir=$3
shift 3
if ! [[ $shards =~ ^[1-9][0-9]*$ ]]; then
  echo "$0: N must be a whole number >= 1, not '$shards'" >&2
  exit 2
fi
[[ -f $config ]] || { echo "$0: no config $config" >&2; exit 2; }
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${BOUNCE_BIN:-$root/build/app/bounce}
[[ -x $bin ]] || { echo "$0: no bounce executable at $bin (build it, or set BOUNCE_BIN)" >&2; exit 2; }
config=$(realpath "$config")
mkdir -p "$dir/logs"
dir=$(realpath "$dir")
# The config is checked here, before anything is queued: a typo fails now, not in N jobs.
"$bin" bench --config "$config" --list-tasks "$@" >/dev/null

export BOUNCE_BIN=$bin BOUNCE_CONFIG=$config BOUNCE_OUT=$dir BOUNCE_BENCH_ARGS="$*"
array=$(sbatch --parsable --array="0-$((shards - 1))" --chdir="$root" --output="$dir/logs/shard-%A_%a.log" \
  --export=ALL "$root/scripts/slurm/study.sbatch")
array=${array%%;*}
merge=$(sbatch --parsable --job-name=bounce-merge --dependency="afterany:$array" --chdir="$root" \
  --output="$dir/logs/merge-%j.log" --export=ALL --wrap="\"$bin\" bench --merge \"$dir\" --out \"$dir\"")
merge=${merge%%;*}
echo "array job $array ($shards shards of $config into $dir)"
echo "merge job $merge (after the array: $dir/report.html; log $dir/logs/merge-$merge.log)"
