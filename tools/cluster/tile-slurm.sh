#!/usr/bin/env bash
# Tiled decimation as a Slurm job array: plan on the submitting node, one array task per
# tile (`decimate tile run` reads SLURM_ARRAY_TASK_ID), merge once every task has succeeded
# (--dependency=afterok; cancelled if a task fails). See docs/cluster.md.
# usage: tools/cluster/tile-slurm.sh IN WORKDIR OUT [plan options] (-p P | --keep-triangles T)
# WORKDIR must be on a file system every node sees. DECIMATE names the binary; extra sbatch
# options (partition, account) go in SBATCH_OPTIONS, e.g. "--partition=cpu --mem=4G".
# WAIT=1 returns only when the merge has finished, with its exit status (sbatch --wait).
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '5,8p' "$0" >&2
  exit 2
fi
in=$1 work=$2 out=$3
shift 3
decimate=${DECIMATE:-decimate}
"$decimate" tile plan "$in" --work "$work" "$@"
tiles=$(grep -c '"index"' "$work/manifest.json")
# shellcheck disable=SC2086
job=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array=0-$((tiles - 1)) --job-name=decimate-tiles \
  --output="$work/slurm-%A_%a.log" --wrap="'$decimate' tile run '$work'")
echo "submitted array $job ($tiles tiles); 'decimate tile status $work' shows progress" >&2
wait=()
[ "${WAIT:-0}" = 1 ] && wait=(--wait)
# shellcheck disable=SC2086
sbatch --parsable ${SBATCH_OPTIONS:-} "${wait[@]}" --dependency=afterok:"$job" \
  --kill-on-invalid-dep=yes --job-name=decimate-merge \
  --output="$work/slurm-merge-%j.log" --wrap="'$decimate' tile merge '$work' -o '$out'"
# sbatch --wait says 0 for a merge cancelled by a failed tile: the output file tells.
if [ "${WAIT:-0}" = 1 ] && ! [ "$out" -nt "$work/manifest.json" ]; then
  echo "tile-slurm.sh: no merge: tiles failed ($work/slurm-${job}_*.log):" >&2
  "$decimate" tile status "$work" | grep pending >&2 || true
  exit 1
fi
