#!/usr/bin/env bash
# The differential tester for as long as you like: N random scenes (default
# 200), each rendered on the GPU and with the CPU reference and compared as
# `render --check` does. Disagreements are kept in build/difftest/ with the
# command that shows each; the exit status is 2 when there is any.
#
#   scripts/difftest.sh [N] [vkray difftest options]
#   scripts/difftest.sh 5000 --seed 10000 --variant all   a long run, one compile per mode
#   scripts/difftest.sh 200 --precision naive             the textbook mode (disagrees by design)
set -euo pipefail
cd "$(dirname "$0")/.."
scenes="${1:-200}"
shift || true
scripts/install-deps.sh
scripts/build.sh >/dev/null
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
exec build/vkray difftest --scenes "$scenes" --out build/difftest "$@"
