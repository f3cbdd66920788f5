#!/usr/bin/env bash
# README command 2: install what is missing, build, and run the whole test
# suite (GoogleTest under ctest). lavapipe's thread count is pinned so GPU
# tests behave the same on every machine.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
export LP_NUM_THREADS=2
cd build && ctest --output-on-failure -j 2 "$@"
