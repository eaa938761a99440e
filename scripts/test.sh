#!/bin/sh
# Quick start, step 2: every test through ctest (C++ core, batch macro under klayout -b, GUI),
# then the core under libFuzzer with AddressSanitizer and UndefinedBehaviorSanitizer for a
# bounded time (LINF_FUZZ_SECONDS, default 60; 0 skips it).
set -e
cd "$(dirname "$0")/.."
./scripts/deps.sh
./scripts/build.sh
(cd build && ctest --output-on-failure "$@")
[ "${LINF_FUZZ_SECONDS:-60}" -gt 0 ] && ./scripts/fuzz.sh "${LINF_FUZZ_SECONDS:-60}"
exit 0
