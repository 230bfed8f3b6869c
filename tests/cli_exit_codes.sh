#!/bin/sh
# Runs the real relief binary: help exits 0; bad input exits 2 and leaves no file behind.
set -u
relief="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$relief" --help >/dev/null || fail "--help did not exit 0"
"$relief" stages --help >/dev/null || fail "stages --help did not exit 0"

expect_bad_input() {
  "$relief" "$@" >"$work/stdout" 2>"$work/stderr"
  code=$?
  [ "$code" -eq 2 ] || fail "'$*' exited $code, expected 2"
  grep -q "relief: error:" "$work/stderr" || fail "'$*' printed no error message"
  [ ! -e "$work/out" ] || fail "'$*' left $work/out behind"
}

printf '{"terrain": {"r": 1}}' >"$work/bad.json"
expect_bad_input stages "$work/bad.json" --out "$work/out"
expect_bad_input stages --set terrain.lattice_size=100 --out "$work/out"
expect_bad_input stages --set grid.width=1 --out "$work/out"
expect_bad_input stages --threads -1 --out "$work/out"
expect_bad_input render --set viewport.width=0 -o "$work/out"
expect_bad_input render -o "$work/out.jpg"
printf '4 4\n0 0 2\n' >"$work/soup.txt"
expect_bad_input raster "$work/soup.txt" --out "$work/out"
expect_bad_input nonsense-command
echo "exit codes as documented"
