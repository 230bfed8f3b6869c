#!/bin/bash
# Submits a relief render or path to Slurm as N shards and one stitch job (docs/shards.md,
# "Slurm"):
#
#   tools/slurm/submit.sh N PARTS OUT RELIEF render|reference|path ARGS...
#
# a job array of N tasks (render_shards.sbatch: task I renders shard I/N into the directory
# PARTS) and a stitch job (stitch.sbatch) that starts once every task succeeded
# (--dependency=afterok) and writes OUT: the image, bytes identical to one `relief render` or
# `relief reference` (with the reference's float image, and a render's extra outputs named in
# RELIEF_OUTPUTS: stitch.sbatch), or the directory of the path's frames. Prints the two job ids, "ARRAY STITCH". Extra sbatch
# options (a partition, a time limit) go in SBATCH_* variables, which sbatch reads itself.
set -euo pipefail
if (($# < 5)); then
  echo "usage: $0 N PARTS OUT RELIEF render|reference|path ARGS..." >&2
  exit 2
fi
count=$1
parts=$2
out=$3
relief=$4
command=$5
shift 5
here=$(cd "$(dirname "$0")" && pwd)
if ! [[ "$count" =~ ^[1-9][0-9]*$ ]]; then
  echo "submit.sh: N = '$count' is not a whole number of at least 1" >&2
  exit 2
fi
mkdir -p "$parts"
array=$(sbatch --parsable --array="0-$((count - 1))" --output="$parts/slurm-%A_%a.out" \
          --export="ALL,RELIEF_PARTS=$parts" "$here/render_shards.sbatch" "$relief" "$command" "$@")
array=${array%%;*}
stitch=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes \
           --output="$parts/slurm-stitch-%j.out" "$here/stitch.sbatch" "$relief" "$command" \
           "$parts" "$out")
echo "$array ${stitch%%;*}"
