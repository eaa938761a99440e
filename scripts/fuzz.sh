#!/bin/sh
# Builds the libFuzzer target with clang, AddressSanitizer and UndefinedBehaviorSanitizer and
# runs it for a bounded time (default 60 s): the core's checkers are the oracle. A finding
# leaves its input in build-fuzz/ (crash-*) and fails the run; it becomes a regression test.
#   scripts/fuzz.sh [SECONDS]
set -e
cd "$(dirname "$0")/.."
seconds="${1:-60}"
cmake -S tests/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo > build-fuzz.log 2>&1 \
  || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j"$(nproc)" >> build-fuzz.log 2>&1 || { tail -40 build-fuzz.log; exit 1; }
cd build-fuzz
status=0
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
  ./fuzz_core -max_total_time="$seconds" -seed=1 -max_len=64 -len_control=0 -print_final_stats=1 \
  > fuzz.log 2>&1 || status=$?
grep -E "^(Done|stat::number_of_executed_units|stat::peak_rss_mb)|ERROR|SUMMARY|rejected|farthest vertex|crash-" fuzz.log | head -20
if [ "$status" -ne 0 ]; then
  tail -60 fuzz.log
  echo "fuzzing found a failure (exit $status); its input is in build-fuzz/crash-*"
  exit "$status"
fi
echo "fuzzing: no finding in $seconds s"
