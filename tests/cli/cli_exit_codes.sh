#!/bin/sh
# Runs the real relief binary: help exits 0; bad input exits 2 and leaves no file behind;
# a job beyond ulimit -v is refused by its estimate, never an abort.
# Usage: cli_exit_codes.sh RELIEF SANITIZED (SANITIZED: 1 in the ASan build, else 0)
set -u
relief="$1"
sanitized="${2:-0}"
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
  [ ! -e "$work/out" ] && [ ! -e "$work/out.png" ] || fail "'$*' left an output behind"
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
expect_bad_input render --max-memory 32M -o "$work/out.png"
mkfifo "$work/fifo.json"
expect_bad_input render "$work/fifo.json" -o "$work/out.png"
expect_bad_input raster /dev/zero --out "$work/out"

# relief compare exits as idiff does: 0 pass, 2 failure, 3 sizes differ, 4 anything that is not a
# comparison (an unreadable or special file, a bad option), never a hang on a FIFO.
"$relief" compare --help >/dev/null || fail "compare --help did not exit 0"
"$relief" render --set viewport.width=16 --set viewport.height=12 --set grid.width=8 \
  --set grid.height=8 -o "$work/a.png" >/dev/null || fail "render for compare failed"
"$relief" render --set viewport.width=16 --set viewport.height=10 --set grid.width=8 \
  --set grid.height=8 -o "$work/short.png" >/dev/null || fail "render for compare failed"
"$relief" render --set viewport.width=16 --set viewport.height=12 --set grid.width=8 \
  --set grid.height=8 --set camera.yaw_deg=90 -o "$work/b.png" >/dev/null || fail "render failed"
expect_compare() {
  want="$1"
  shift
  timeout 60 "$relief" compare "$@" >"$work/stdout" 2>"$work/stderr"
  code=$?
  [ "$code" -eq "$want" ] || fail "'compare $*' exited $code, expected $want"
  if [ "$want" -eq 4 ]; then
    grep -q "relief: error:" "$work/stderr" || fail "'compare $*' printed no error message"
  fi
  [ ! -e "$work/out.json" ] || [ "$want" -lt 4 ] || fail "'compare $*' left an output behind"
  rm -f "$work/out.json"
}
expect_compare 0 "$work/a.png" "$work/a.png" --json "$work/out.json"
expect_compare 2 "$work/a.png" "$work/b.png"
expect_compare 3 "$work/a.png" "$work/short.png"
expect_compare 4 "$work/a.png" "$work/fifo.json" --json "$work/out.json"
expect_compare 4 "$work/a.png" /dev/zero --json "$work/out.json"
expect_compare 4 "$work/a.png" "$work" --json "$work/out.json"
expect_compare 4 "$work/a.png" "$work/missing.png" --json "$work/out.json"
expect_compare 4 "$work/a.png" "$work/bad.json" --json "$work/out.json"
expect_compare 4 "$work/a.png"
expect_compare 4 "$work/a.png" "$work/a.png" --fail -1
expect_compare 4 "$work/a.png" "$work/a.png" --diff "$work/out.jpg"

# The scene printed to a full disk was not printed: exit 1.
if [ -w /dev/full ]; then
  "$relief" scene >/dev/full 2>"$work/stderr"
  code=$?
  [ "$code" -eq 1 ] || fail "'relief scene >/dev/full' exited $code, expected 1"
fi

# An address-space limit (ulimit -v) is part of the budget: a job beyond it is refused by its
# estimate (exit 2, nothing written), where it once ran into std::bad_alloc. AddressSanitizer
# reserves terabytes of address space for its shadow memory, so the sanitizer build cannot run
# under such a limit.
if [ "$sanitized" != 1 ]; then
  (
    ulimit -v 1500000
    "$relief" render --set viewport.width=8192 --set viewport.height=8192 -o "$work/out.png" \
      --float "$work/out.pfm" >"$work/stdout" 2>"$work/stderr"
  )
  code=$?
  [ "$code" -eq 2 ] || fail "a render beyond ulimit -v exited $code, expected 2"
  grep -q "relief: error: this render needs about" "$work/stderr" || fail "no estimate message"
  [ ! -e "$work/out.png" ] || fail "a render beyond ulimit -v left $work/out.png behind"
fi
echo "exit codes as documented"
