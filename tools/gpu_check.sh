#!/bin/sh
# The GL backend on a machine with a GPU, in one command: build (unless given binaries), the
# [gl] tests, relief crosscheck of every preset, and the GL and simd frame times of every
# preset side by side; a summary table last. docs/gl-backend.md ("On a GPU") says what each
# figure means and what it was on an NVIDIA H100.
#
#   tools/gpu_check.sh [OUT_DIR]          build into build-gpu/ (Release), results into OUT_DIR
#   RELIEF_BIN_DIR=DIR tools/gpu_check.sh  use DIR's relief and relief_gl_tests instead
#   RELIEF_PRESETS, RELIEF_GL_TESTS (a Catch2 test spec), RELIEF_REPEAT: fewer for a quick look
#   RELIEF_SET="viewport.width=160 viewport.height=128": --set assignments for every render
#     (split at spaces: an assignment whose value holds a space cannot be given here)
#
# OUT_DIR (default gpu-check/, relative to the repository's root) receives gl_tests.txt (the
# console report) and gl_tests.xml (JUnit), one crosscheck folder per preset (both images,
# heat maps, crosscheck.txt and .json), stats/ (every relief render --stats report) and
# summary.txt. Exit 0 when every test passed and every render and crosscheck ran (a
# crosscheck's verdict is reported in the table, not judged), 1 otherwise.
set -u
cd "$(dirname "$0")/.." || exit 1
out=${1:-gpu-check}
repeat=${RELIEF_REPEAT:-9}
mkdir -p "$out/stats" || exit 1

if [ -n "${RELIEF_BIN_DIR:-}" ]; then
  bin=$RELIEF_BIN_DIR
else
  if ! { cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release >"$out/build.log" 2>&1 &&
    cmake --build build-gpu -j"$(nproc)" --target relief relief_gl_tests >>"$out/build.log" 2>&1; }; then
    tail -30 "$out/build.log"
    echo "gpu_check: the build failed ($out/build.log)"
    exit 1
  fi
  mkdir -p build-gpu/gpu-bin
  ln -sf ../tools/relief ../tests/relief_gl_tests build-gpu/gpu-bin/
  bin=build-gpu/gpu-bin
fi
relief=$bin/relief
sets=""
for assignment in ${RELIEF_SET:-}; do
  sets="$sets --set $assignment"
done
export RELIEF_BINARY="$relief"  # the tests that run the binary run this one

{
  echo "gpu_check: $(date -u +%Y-%m-%dT%H:%MZ), $(git rev-parse --short HEAD 2>/dev/null || echo 'no git')"
  command -v nvidia-smi >/dev/null &&
    nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
  grep -m1 'model name' /proc/cpuinfo
  echo "cores: $(nproc)"
  "$relief" info | grep -E '^relief|^simd backend target|^GL backend'
} >"$out/summary.txt" 2>&1
"$relief" info >"$out/info.txt" 2>&1

failed=0
tests=${RELIEF_GL_TESTS:-[gl]}  # a Catch2 test spec
# The [gl] tests: the console report (every failure's expansion) and a JUnit copy.
"$bin/relief_gl_tests" "$tests" >"$out/gl_tests.txt" 2>&1
tests_code=$?
"$bin/relief_gl_tests" "$tests" --reporter junit --out "$out/gl_tests.xml" >/dev/null 2>&1
[ "$tests_code" -eq 0 ] || failed=1
printf '\n[gl] tests: %s (exit %s)\n' \
  "$(grep -E '^(test cases|All tests passed)' "$out/gl_tests.txt" | tail -1)" "$tests_code" \
  >>"$out/summary.txt"

printf '\n%-9s %-9s %9s %9s %8s %10s %8s %8s\n' preset crosscheck "gl ms" "simd ms" \
  "gl/simd" "tri diff" "max sRGB" "PSNR" >>"$out/summary.txt"
presets=$("$relief" render --help 2>/dev/null | sed -n 's/.*a preset name (\([a-z, ]*\)).*/\1/p' | tr -d ,)
presets=${RELIEF_PRESETS:-$presets}
[ -n "$presets" ] || { echo "gpu_check: relief render --help lists no presets"; exit 1; }
for p in $presets; do
  # A shadowed preset has no GL twin yet: the GL backend refuses it (exit 2, naming
  # lighting.shadows), and only the simd time is reported; any other GL failure fails the run.
  # shellcheck disable=SC2086 # $sets: one word per --set and assignment
  "$relief" render "$p" $sets --backend gl --repeat "$repeat" --stats -o "$out/stats/$p-gl.png" \
    >"$out/stats/$p-gl.txt" 2>&1
  gl_code=$?
  # shellcheck disable=SC2086
  "$relief" render "$p" $sets --backend simd --repeat "$repeat" --stats -o "$out/stats/$p-simd.png" \
    >"$out/stats/$p-simd.txt" 2>&1 || failed=1
  gl_ms=$(awk '$1 == "frame" && NF == 2 {print $2}' "$out/stats/$p-gl.txt")
  simd_ms=$(awk '$1 == "frame" && NF == 2 {print $2}' "$out/stats/$p-simd.txt")
  verdict=refused tri=- srgb=- psnr=- ratio=-
  if [ "$gl_code" -eq 0 ]; then
    # The verdict is reported, not judged: the crosscheck's rule does not yet explain every
    # pixel a GPU's sub-pixel snapping moves (docs/gl-backend.md, "On a GPU").
    # shellcheck disable=SC2086
    "$relief" crosscheck "$p" $sets --out "$out/$p" --repeat 3 >"$out/$p.log" 2>&1
    [ "$?" -le 2 ] || failed=1
    verdict=$(tail -1 "$out/$p.log")
    tri=$(sed -n 's/.*pixels whose triangle differs *\([0-9]*\) (\(.*\)).*/\2/p' "$out/$p.log")
    srgb=$(sed -n 's/^9 sRGB image *max error (codes), PSNR (dB) *\([^,]*\), \(.*\)/\1/p' "$out/$p.log")
    psnr=$(sed -n 's/^9 sRGB image *max error (codes), PSNR (dB) *\([^,]*\), \(.*\)/\2/p' "$out/$p.log")
    ratio=$(awk -v g="$gl_ms" -v s="$simd_ms" 'BEGIN {if (s > 0) printf "%.2f", g / s}')
  elif [ "$gl_code" -ne 2 ] || ! grep -q 'lighting.shadows' "$out/stats/$p-gl.txt"; then
    verdict=GL-ERROR
    failed=1
  fi
  printf '%-9s %-9s %9s %9s %8s %10s %8s %8s\n' "$p" "$verdict" "${gl_ms:--}" \
    "${simd_ms:--}" "$ratio" "$tri" "$srgb" "$psnr" >>"$out/summary.txt"
done
echo "frame times: median of $repeat, relief render --stats (gl: every GL pass on the GPU;" \
  "simd: $(nproc) threads)" >>"$out/summary.txt"
cat "$out/summary.txt"
[ "$tests_code" -eq 0 ] || tail -60 "$out/gl_tests.txt"
exit "$failed"
