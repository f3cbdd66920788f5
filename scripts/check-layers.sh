#!/usr/bin/env bash
# Fails when a file under host/ includes from a layer above its own, or from a
# sibling on its rank (the GPU renderer and the CPU reference stay
# independent of each other). The order is documented in docs/architecture.md.
# Usage: scripts/check-layers.sh [REPOSITORY]   (default: this checkout)
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

# Rank of each layer; a file may include its own layer and lower ranks.
# shaders/ holds the headers shared by C++ and GLSL (layout.h, sampling.h),
# which include nothing of host/.
declare -A rank=(
  [util]=0 [shaders]=0
  [image]=1
  [scene]=2
  [render]=3
  [gpu]=4 [reference]=4
  [dist]=5
  [numerics]=6
  [app]=7
)

status=0
checked=0
while IFS= read -r -d '' file; do
  layer=${file#host/}
  layer=${layer%%/*}
  if [ -z "${rank[$layer]+set}" ]; then
    echo "$file: the layer '$layer' is not in scripts/check-layers.sh's list; add it there" \
         "and to docs/architecture.md" >&2
    status=1
    continue
  fi
  checked=$((checked + 1))
  while IFS=: read -r line target; do
    target=${target#*\"}
    used=${target%%/*}
    [ "$used" = "$layer" ] && continue
    [ "$used" = "$target" ] && continue   # "file.h" beside the includer
    if [ -z "${rank[$used]+set}" ]; then
      echo "$file:$line: includes \"$target\" from '$used', which is no layer" >&2
      status=1
    elif [ "${rank[$used]}" -ge "${rank[$layer]}" ]; then
      echo "$file:$line: $layer (rank ${rank[$layer]}) includes \"$target\" from $used" \
           "(rank ${rank[$used]}): a layer includes only from layers below it" >&2
      status=1
    fi
  done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$file" |
           sed -E 's/^([0-9]+):.*#[[:space:]]*include[[:space:]]*"([^"]*)".*/\1:"\2/')
done < <(find host -type f \( -name '*.h' -o -name '*.cpp' \) -print0 | sort -z)

if [ "$checked" -eq 0 ]; then
  echo "check-layers: no file under host/ (run from the repository)" >&2
  exit 1
fi
[ "$status" -eq 0 ] && echo "check-layers: $checked files, no include from a layer above its own"
exit "$status"
