#!/bin/sh
# Quick start, step 2: every test through ctest (C++ core, batch macro under klayout -b, GUI),
# then the core under libFuzzer with AddressSanitizer and UndefinedBehaviorSanitizer for a
# bounded time (LINF_FUZZ_SECONDS, default 60; 0 skips it).
# The tests on the shared public layouts report SKIPPED where ../shared/data is missing: the
# last lines say how many tests ran, and which were skipped and why.
set -e
cd "$(dirname "$0")/.."
./scripts/deps.sh
./scripts/build.sh
status=0
(cd build && ctest --output-on-failure -O ctest.log "$@") || status=$?
[ -f build/ctest.log ] || exit "$status"
total=$(sed -n 's/.* tests failed out of \([0-9]*\)$/\1/p' build/ctest.log)
skipped=$(grep -c ' (Skipped)$' build/ctest.log || true)
echo "tests: $((${total:-0} - skipped)) of ${total:-0} ran, $skipped skipped"
if [ "$skipped" -gt 0 ]; then
  # Each skipped test with the reason it printed (LastTest.log holds every test's output).
  awk '/^[0-9]+\/[0-9]+ Test: / { name = $3 } /^SKIPPED: / { print "  skipped " name ": " substr($0, 10) }' \
    build/Testing/Temporary/LastTest.log
fi
[ "$status" -eq 0 ] || exit "$status"
[ "${LINF_FUZZ_SECONDS:-60}" -gt 0 ] && ./scripts/fuzz.sh "${LINF_FUZZ_SECONDS:-60}"
exit 0
