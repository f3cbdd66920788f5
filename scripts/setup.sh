#!/usr/bin/env bash
# README command 1: install what is missing, build, and render the default
# scene on the GPU (lavapipe when there is no GPU).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/vkray render scenes/default.sdl -o build/default.png
