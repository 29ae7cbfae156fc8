#!/usr/bin/env bash
# Tiled decimation with GNU parallel as the scheduler: plan, one `decimate tile run` process
# per tile (JOBS at a time, DEFAULT: the number of cores), merge. See docs/cluster.md.
# usage: tools/cluster/tile-parallel.sh IN WORKDIR OUT [plan options: --tiles N | --tile-triangles M]
#        (-p P | --keep-triangles T)
# DECIMATE names the binary (DEFAULT: decimate on the PATH).
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '4,6p' "$0" >&2
  exit 2
fi
in=$1 work=$2 out=$3
shift 3
decimate=${DECIMATE:-decimate}
command -v parallel >/dev/null || { echo "tile-parallel.sh: GNU parallel is not installed" >&2; exit 2; }
"$decimate" tile plan "$in" --work "$work" "$@"
tiles=$(grep -c '"index"' "$work/manifest.json")
# --halt now,fail=1: one failed tile stops the rest; re-running this script redoes it.
seq 0 $((tiles - 1)) | parallel --halt now,fail=1 -j "${JOBS:-$(nproc)}" "$decimate" tile run "$work" {}
"$decimate" tile status "$work" | tail -n 1
"$decimate" tile merge "$work" -o "$out"
