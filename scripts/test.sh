#!/bin/sh
# Quick start, step 2: every test through ctest (C++ core, batch macro under klayout -b, GUI).
set -e
cd "$(dirname "$0")/.."
./scripts/deps.sh
./scripts/build.sh
cd build && ctest --output-on-failure "$@"
