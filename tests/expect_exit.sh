#!/bin/sh
# Runs a command that must fail cleanly: it passes only where the command exits with CODE, its
# output (stdout and stderr) matches the extended regular expression MESSAGE, and no uncaught
# exception is reported (Python's "Traceback", KLayout's "ERROR: " with the stack): a crash
# exits non-zero too, so a plain "it failed" proves nothing.
#   tests/expect_exit.sh CODE MESSAGE -- COMMAND [ARG...]
if [ "$#" -lt 4 ] || [ "$3" != "--" ]; then
  echo "usage: expect_exit.sh CODE MESSAGE -- COMMAND [ARG...]" >&2
  exit 2
fi
code=$1
message=$2
shift 3
out=$("$@" 2>&1)
rc=$?
printf '%s\n' "$out"
status=0
if [ "$rc" -ne "$code" ]; then
  echo "FAIL: exit $rc, expected $code"
  status=1
fi
if ! printf '%s\n' "$out" | grep -Eq -- "$message"; then
  echo "FAIL: no line matches: $message"
  status=1
fi
if printf '%s\n' "$out" | grep -Eq "Traceback|^ERROR: "; then
  echo "FAIL: an uncaught exception"
  status=1
fi
exit $status
