#!/usr/bin/env bash
# Configures (Release, Ninja, MPI required: install-deps.sh installs it) and
# builds into build/; incremental after the first run.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVKRAY_MPI=ON
cmake --build build
