#!/bin/sh
# Runs a test's command where every input it names exists; otherwise prints why and exits 77,
# which ctest reports as skipped (the test's SKIP_RETURN_CODE) rather than passed or failed.
#   tests/skip_unless.sh PATH... -- COMMAND [ARG...]
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  if [ ! -e "$1" ]; then
    echo "SKIPPED: $1 missing"
    exit 77
  fi
  shift
done
if [ "$1" != "--" ]; then
  echo "usage: skip_unless.sh PATH... -- COMMAND [ARG...]" >&2
  exit 2
fi
shift
exec "$@"
