#!/bin/sh
# Builds the libFuzzer target with clang, AddressSanitizer and UndefinedBehaviorSanitizer (in
# build-fuzz/) and runs it for a bounded time (default 60 s) with a fresh random seed, printed:
# the core's checkers and brute force are the oracle (tests/fuzz/fuzz_core.cpp). It starts from a
# copy of the corpus kept in tests/fuzz/corpus/ in a temporary folder, so the checkout is never
# written. A finding (crash-*, leak-*, timeout-*, oom-*) is saved in build/fuzz-findings/, its
# path printed, and fails the run; add it to tests/fuzz/corpus/ once fixed.
#   scripts/fuzz.sh [SECONDS]
#   LINF_FUZZ_SEED=N scripts/fuzz.sh   repeats a run's seed
#   LINF_FUZZ_STRICT=1 scripts/fuzz.sh  the known, not yet fixed faults (tests/fuzz/known.hpp) fail it too
set -e
cd "$(dirname "$0")/.."
seconds="${1:-60}"
cmake -S tests/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo > build-fuzz.log 2>&1 \
  || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j"$(nproc)" >> build-fuzz.log 2>&1 || { tail -40 build-fuzz.log; exit 1; }
seed="${LINF_FUZZ_SEED:-$(( $(od -An -N4 -tu4 /dev/urandom) % 2147483646 + 1 ))}"
findings="$PWD/build/fuzz-findings"
work=$(mktemp -d "${TMPDIR:-/tmp}/linf-fuzz.XXXXXX")
trap 'rm -rf "$work"' EXIT
cp -R tests/fuzz/corpus "$work/corpus"
mkdir -p "$findings"
echo "fuzzing for $seconds s, seed $seed ($(ls tests/fuzz/corpus | wc -l) corpus inputs; LINF_FUZZ_SEED=$seed repeats it)"
status=0
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
  build-fuzz/fuzz_core "$work/corpus" -seed="$seed" -max_total_time="$seconds" -timeout=60 -max_len=256 \
  -len_control=0 -artifact_prefix="$findings/" -print_final_stats=1 > build-fuzz/fuzz.log 2>&1 || status=$?
grep -E "^(Done|stat::number_of_executed_units|stat::new_units_added|stat::peak_rss_mb)|^known:|INITED|ERROR|SUMMARY|fuzz finding" \
  build-fuzz/fuzz.log | head -20
if [ "$status" -ne 0 ]; then
  tail -60 build-fuzz/fuzz.log
  written=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' build-fuzz/fuzz.log)
  echo "fuzzing found a failure (exit $status, seed $seed); its input: ${written:-none written, see build-fuzz/fuzz.log}"
  [ -n "$written" ] && echo "repeat it: build-fuzz/fuzz_core $written"
  exit "$status"
fi
echo "fuzzing: no finding in $seconds s (seed $seed, $(ls "$work/corpus" | wc -l) inputs in the corpus at the end)"
