#!/usr/bin/env bash
# Speed-up of `vkray render` across MPI ranks on this machine:
# one process with LP_NUM_THREADS=CORES against mpirun with 1 rank (unbound,
# all cores) and with 2 ranks (mpirun binds each to a core of its own,
# LP_NUM_THREADS then follows the binding). Each configuration runs RUNS
# times, interleaved, and the median render time is kept; rank 0's hand-out
# time per tile comes from its own report. Not a test: it prints a table.
#
#   bench/mpi_speedup.sh [SCENE] [WxH] [SPP] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
scene="${1:-scenes/whitted.sdl}"
size="${2:-1920x1080}"
spp="${3:-4}"
runs="${4:-5}"
cores=$(nproc)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

render() {  # render NAME COMMAND...: prints the "gpu render:" line
  "$@" render "$scene" -o "$out/image.png" --size "$size" --spp "$spp" --quiet 2>&1 |
    grep '^gpu render:'
}
declare -A times lines
for ((i = 0; i < runs; i++)); do
  line=$(LP_NUM_THREADS=$cores render build/vkray); times[one]+="$(awk '{print $3}' <<<"$line") "
  lines[one]=$line
  line=$(render mpirun --bind-to none -np 1 build/vkray); times[np1]+="$(awk '{print $3}' <<<"$line") "
  lines[np1]=$line
  line=$(render mpirun --oversubscribe -np 2 build/vkray); times[np2]+="$(awk '{print $3}' <<<"$line") "
  lines[np2]=$line
done
median() { tr ' ' '\n' <<<"$1" | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

echo "scene $scene, $size, $spp spp, $runs runs each (median), $cores cores, $(date -u +%F)"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
base=$(median "${times[one]}")
printf '%-42s %10s %9s\n' configuration "render s" speed-up
printf '%-42s %10s %9s\n' "1 process, LP_NUM_THREADS=$cores" "$base" 1.00
for k in np1 np2; do
  m=$(median "${times[$k]}")
  label=$([ $k = np1 ] && echo "mpirun -np 1 (unbound, $cores lavapipe threads)" || echo "mpirun -np 2 (a core each, 1 thread each)")
  printf '%-42s %10s %9.2f\n' "$label" "$m" "$(awk -v a="$base" -v b="$m" 'BEGIN {print a / b}')"
done
echo "last 2-rank report: ${lines[np2]}"
