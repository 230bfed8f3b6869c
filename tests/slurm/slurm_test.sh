#!/bin/bash
# Slurm, the real one (docs/shards.md, "Slurm"): a one-node Slurm started here from Debian's
# packages (tools/slurm/local_cluster.sh), a 4-task job array and its stitch job for a large
# image and for a 64-frame path (tools/slurm/submit.sh), and the bytes checked against the
# same image and path rendered in one process. The daemons are stopped whatever happens. A
# machine that cannot start them fails the test with the reason; nothing is skipped.
#
#   tests/slurm/slurm_test.sh RELIEF SOURCE_DIR
# RELIEF_SLURM_IMAGE_SIDE: the image's side (8192; the sanitizer build's ctest sets less).
set -euo pipefail
relief=$1
source_dir=$2
side=${RELIEF_SLURM_IMAGE_SIDE:-8192}
frames=64
slurm="$source_dir/tools/slurm"
work=$(mktemp -d /tmp/relief-slurm-test.XXXXXX)
cleanup() {
  "$slurm/local_cluster.sh" stop "$work/cluster" || true
  rm -rf "$work"
}
trap cleanup EXIT
started=$(date +%s)

"$slurm/local_cluster.sh" start "$work/cluster"
export SLURM_CONF="$work/cluster/slurm.conf"

# Waits for stitch job $1 (of array $2) to end; fails unless it COMPLETED, with the state of
# each of the array's tasks and the output of those that did not complete (a stitch job is
# cancelled when a task fails: --kill-on-invalid-dep).
wait_for_job() {
  local id=$1 array=$2 state=""
  for _ in $(seq 1800); do
    state=$(scontrol show job "$id" -o 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2)
    case "$state" in
      COMPLETED) return 0 ;;
      FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | PREEMPTED | BOOT_FAIL | DEADLINE)
        echo "slurm_test: job $id ended $state" >&2
        report_tasks "$array"
        cat "$work"/*/slurm-stitch-"$id".out >&2 2>/dev/null || true
        return 1 ;;
    esac
    sleep 0.5
  done
  echo "slurm_test: job $id still ${state:-unknown} after 900 s" >&2
  report_tasks "$array"
  return 1
}

# The state and exit code of each task of array $1, and the last lines of the output of each
# task that did not complete.
report_tasks() {
  local line task state
  scontrol show job "$1" -o 2>/dev/null | while read -r line; do
    task=$(grep -o 'ArrayTaskId=[0-9]*' <<<"$line" | cut -d= -f2)
    state=$(grep -o 'JobState=[A-Z_]*' <<<"$line" | cut -d= -f2)
    echo "slurm_test: array $1 task ${task:-?}: $state ($(grep -o 'ExitCode=[0-9:]*' <<<"$line"))" >&2
    if [[ "$state" != COMPLETED && -n "$task" ]]; then
      tail -n 40 "$work"/*/slurm-"$1"_"$task".out >&2 2>/dev/null || true
    fi
  done
}

image=(default --set "viewport.width=$side" --set "viewport.height=$side")
path=(planet --frames "$frames" --from-altitude 3e5 --to-altitude 800
      --set viewport.width=160 --set viewport.height=120 --set grid.width=96 --set grid.height=96)

read -r image_array image_stitch < <("$slurm/submit.sh" 4 "$work/image-parts" "$work/stitched.png" \
                                     "$relief" render "${image[@]}")
read -r path_array path_stitch < <("$slurm/submit.sh" 4 "$work/path-parts" "$work/stitched-path" \
                                   "$relief" path "${path[@]}")
# A small image with extra outputs (RELIEF_OUTPUTS) and a ground truth, 4 tasks each.
small=(lake --set viewport.width=320 --set viewport.height=256 --set grid.width=128
       --set grid.height=128)
read -r extras_array extras_stitch < <(RELIEF_OUTPUTS=float,depth,primitive "$slurm/submit.sh" 4 \
                                       "$work/extras-parts" "$work/extras.png" "$relief" render \
                                       "${small[@]}")
reference=("${small[@]}" --supersample 2 --grid-scale 2)
read -r reference_array reference_stitch < <("$slurm/submit.sh" 4 "$work/reference-parts" \
                                             "$work/reference.png" "$relief" reference \
                                             "${reference[@]}")
echo "slurm_test: submitted arrays $image_array, $path_array, $extras_array and" \
     "$reference_array, stitch jobs $image_stitch, $path_stitch, $extras_stitch and $reference_stitch"

# The same image and path in one process, while Slurm works.
"$relief" render "${image[@]}" -o "$work/one.png" >/dev/null
"$relief" path "${path[@]}" --out "$work/one-path" >/dev/null
"$relief" render "${small[@]}" -o "$work/one-extras.png" --float "$work/one-extras.float.exr" \
  --depth "$work/one-extras.depth.exr" --primitive "$work/one-extras.primitive.bin" >/dev/null
"$relief" reference "${reference[@]}" -o "$work/one-reference.png" >/dev/null

passed=0
failed=0
wait_for_job "$image_stitch" "$image_array"
if cmp "$work/one.png" "$work/stitched.png"; then
  echo "slurm_test: ${side}x${side} image from 4 tasks: identical ($(md5sum < "$work/one.png" | cut -c1-32))"
  passed=$((passed + 1))
else
  failed=$((failed + 1))
fi
wait_for_job "$path_stitch" "$path_array"
different=0
for frame in "$work"/one-path/frame_*.png; do
  cmp -s "$frame" "$work/stitched-path/$(basename "$frame")" || different=$((different + 1))
done
count=$(ls "$work"/stitched-path/frame_*.png | wc -l)
if ((different == 0 && count == frames)); then
  echo "slurm_test: $frames-frame path from 4 tasks: identical"
  passed=$((passed + 1))
else
  echo "slurm_test: $different of $frames frames differ, $count stitched" >&2
  failed=$((failed + 1))
fi
# Every file of the two small jobs: the same bytes as one process wrote.
same_files() {
  local what=$1
  shift
  for pair in "$@"; do
    if ! cmp "$work/one-${pair}" "$work/${pair}"; then
      failed=$((failed + 1))
      return
    fi
  done
  echo "slurm_test: $what from 4 tasks: identical"
  passed=$((passed + 1))
}
wait_for_job "$extras_stitch" "$extras_array"
same_files "320x256 image with its float, depth and primitive outputs" extras.png \
  extras.float.exr extras.depth.exr extras.primitive.bin
wait_for_job "$reference_stitch" "$reference_array"
same_files "320x256 ground truth (2x2 samples) with its float image" reference.png reference.exr
echo "slurm_test: $(($(date +%s) - started)) s"
echo "$passed passed, $failed failed"
((failed == 0))
