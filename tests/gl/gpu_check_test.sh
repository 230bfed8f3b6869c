#!/bin/sh
# tools/gpu_check.sh as a GPU machine runs it, on this build's binaries and whatever GL the
# machine has (llvmpipe in CI), at a small size: one preset the GL draws and crosschecks, the
# shadowed one it refuses, one [gl] test; the table's rows and the exit code.
# Usage: gpu_check_test.sh RELIEF_BINARY RELIEF_GL_TESTS_BINARY SOURCE_DIR
set -u
work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
mkdir "$work/bin"
ln -s "$1" "$work/bin/relief"
ln -s "$2" "$work/bin/relief_gl_tests"
RELIEF_BIN_DIR="$work/bin" RELIEF_PRESETS="plain sunset" RELIEF_REPEAT=1 \
  RELIEF_GL_TESTS="glShardsStitchToTheBytesOfOneGlRender" \
  RELIEF_SET="viewport.width=160 viewport.height=128 grid.width=96 grid.height=96" \
  "$3/tools/gpu_check.sh" "$work/out" >"$work/log" 2>&1
code=$?
cat "$work/log"
fail() { echo "gpu_check_test: $1"; exit 1; }
[ "$code" -eq 0 ] || fail "exit $code, expected 0"
grep -q '^\[gl\] tests: All tests passed' "$work/log" || fail "the tests' line is missing"
grep -Eq '^plain +(PASS|WARNING) ' "$work/log" || fail "plain's crosscheck row is missing"
grep -Eq '^sunset +refused ' "$work/log" || fail "sunset is not reported as refused"
[ -s "$work/out/plain/crosscheck.json" ] || fail "no crosscheck.json for plain"
[ -s "$work/out/gl_tests.xml" ] || fail "no JUnit report"
echo "gpu_check_test: passed"
