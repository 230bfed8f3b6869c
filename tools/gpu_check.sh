#!/bin/sh
# The GL backend on a machine with a GPU, in one command: build (unless given binaries), the
# [gl] tests, relief crosscheck of every preset, and the GL and simd frame times of every
# preset side by side; a summary table last. docs/gl-backend.md ("On a GPU") says what each
# figure means and what it was on an NVIDIA H100.
#
#   tools/gpu_check.sh [OUT_DIR]          build into build-gpu/ (Release), results into OUT_DIR
#   RELIEF_BIN_DIR=DIR tools/gpu_check.sh  use DIR's relief and relief_gl_tests instead
#   RELIEF_PRESETS, RELIEF_GL_TESTS (a Catch2 test spec), RELIEF_REPEAT: fewer for a quick look
#
# OUT_DIR (default gpu-check/) receives gl_tests.xml (JUnit), gl_tests.txt, one crosscheck
# folder per preset (both images, heat maps, crosscheck.txt and .json), stats/ (every
# relief render --stats report) and summary.txt. Exit 0 when every test passed and every
# crosscheck passed or warned, 1 otherwise.
set -u
cd "$(dirname "$0")/.."
out=${1:-gpu-check}
repeat=${RELIEF_REPEAT:-9}
mkdir -p "$out/stats" || exit 1

if [ -n "${RELIEF_BIN_DIR:-}" ]; then
  bin=$RELIEF_BIN_DIR
else
  cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=Release >"$out/build.log" 2>&1 &&
    cmake --build build-gpu -j"$(nproc)" --target relief relief_gl_tests >>"$out/build.log" 2>&1 ||
    { tail -30 "$out/build.log"; echo "gpu_check: the build failed ($out/build.log)"; exit 1; }
  mkdir -p build-gpu/gpu-bin
  ln -sf ../tools/relief ../tests/relief_gl_tests build-gpu/gpu-bin/
  bin=build-gpu/gpu-bin
fi
relief=$bin/relief
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
# The [gl] tests; Catch2's JUnit report keeps every failure's message.
"$bin/relief_gl_tests" "$tests" --reporter junit --out "$out/gl_tests.xml" >/dev/null 2>&1
tests_code=$?
"$bin/relief_gl_tests" "$tests" --list-test-names-only 2>/dev/null | grep -c . >"$out/gl_test_count.txt"
if [ "$tests_code" -ne 0 ]; then
  failed=1
  # The failing tests again with the console reporter: the expansions a reader wants.
  grep -o 'testcase [^>]*name="[^"]*"[^/]*>[[:space:]]*<failure' "$out/gl_tests.xml" |
    sed 's/.*name="\([^"]*\)".*/\1/' | sort -u >"$out/gl_failed.txt"
  while read -r name; do
    "$bin/relief_gl_tests" "$name" >>"$out/gl_tests.txt" 2>&1
  done <"$out/gl_failed.txt"
fi
printf '\n[gl] tests: %s of %s failed (exit %s)\n' \
  "$(grep -o '<failure' "$out/gl_tests.xml" | wc -l)" "$(cat "$out/gl_test_count.txt")" \
  "$tests_code" >>"$out/summary.txt"

printf '\n%-9s %-9s %9s %9s %8s %10s %8s %8s\n' preset crosscheck "gl ms" "simd ms" \
  "gl/simd" "tri diff" "max sRGB" "PSNR" >>"$out/summary.txt"
presets=$("$relief" render --help 2>/dev/null | sed -n 's/.*a preset name (\([a-z, ]*\)).*/\1/p' | tr -d ,)
presets=${RELIEF_PRESETS:-$presets}
[ -n "$presets" ] || { echo "gpu_check: relief render --help lists no presets"; exit 1; }
for p in $presets; do
  # A shadowed preset has no GL twin yet (the GL backend refuses it): the simd time alone.
  "$relief" render "$p" --backend gl --repeat "$repeat" --stats -o "$out/stats/$p-gl.png" \
    >"$out/stats/$p-gl.txt" 2>&1
  gl_code=$?
  "$relief" render "$p" --backend simd --repeat "$repeat" --stats -o "$out/stats/$p-simd.png" \
    >"$out/stats/$p-simd.txt" 2>&1
  gl_ms=$(awk '$1 == "frame" && NF == 2 {print $2}' "$out/stats/$p-gl.txt")
  simd_ms=$(awk '$1 == "frame" && NF == 2 {print $2}' "$out/stats/$p-simd.txt")
  verdict=refused tri=- srgb=- psnr=- ratio=-
  if [ "$gl_code" -eq 0 ]; then
    "$relief" crosscheck "$p" --out "$out/$p" --repeat 3 >"$out/$p.log" 2>&1
    code=$?
    verdict=$(tail -1 "$out/$p.log")
    [ "$code" -le 1 ] || failed=1
    tri=$(sed -n 's/.*pixels whose triangle differs *\([0-9]*\) (\(.*\)).*/\2/p' "$out/$p.log")
    srgb=$(sed -n 's/^9 sRGB image *max error (codes), PSNR (dB) *\([^,]*\), \(.*\)/\1/p' "$out/$p.log")
    psnr=$(sed -n 's/^9 sRGB image *max error (codes), PSNR (dB) *\([^,]*\), \(.*\)/\2/p' "$out/$p.log")
    ratio=$(awk -v g="$gl_ms" -v s="$simd_ms" 'BEGIN {if (s > 0) printf "%.2f", g / s}')
  fi
  printf '%-9s %-9s %9s %9s %8s %10s %8s %8s\n' "$p" "$verdict" "${gl_ms:--}" \
    "${simd_ms:--}" "$ratio" "$tri" "$srgb" "$psnr" >>"$out/summary.txt"
done
echo "frame times: median of $repeat, relief render --stats (gl: every GL pass on the GPU;" \
  "simd: $(nproc) threads)" >>"$out/summary.txt"
cat "$out/summary.txt"
[ -s "$out/gl_tests.txt" ] && tail -60 "$out/gl_tests.txt"
exit "$failed"
