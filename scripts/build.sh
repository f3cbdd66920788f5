#!/usr/bin/env bash
# Configures (Release, Ninja) and builds into build/; incremental after the first run.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
