#!/bin/sh
# The sanitizer build compiles its default ASan options into every executable
# (cmake/asan_default_options.cc). Each program named here must report them in effect, as
# AddressSanitizer itself prints them (help=1 lists every flag with its current value); a
# program built without the file reports the runtime's default, true.
# Usage: sanitizer_defaults_test.sh PROGRAM...
set -u
status=0
for program in "$@"; do
  # ASan prints its list before main; --help then keeps the program from doing any work.
  flags=$(ASAN_OPTIONS=help=1 "$program" --help 2>&1 >/dev/null)
  value=$(printf '%s\n' "$flags" | grep -A1 '^\s*intercept_tls_get_addr$' | grep -o 'Current Value: [a-z]*')
  if [ "$value" != "Current Value: false" ]; then
    echo "FAIL: $(basename "$program"): intercept_tls_get_addr reports '${value:-nothing}'," \
         "expected 'Current Value: false'"
    status=1
  else
    echo "$(basename "$program"): intercept_tls_get_addr=0"
  fi
done
exit $status
