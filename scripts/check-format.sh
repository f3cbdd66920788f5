#!/usr/bin/env bash
# Fails when a C++ file differs from what clang-format makes of it under the
# repository's .clang-format; it only checks, and rewrites nothing. To format
# your change: clang-format -i FILE... (Debian bookworm's clang-format 14, the
# version CI uses; another version may lay out a few lines otherwise).
# shaders/ is GLSL (layout.h is shared with C++ but written for both) and is
# left as written.
# Usage: scripts/check-format.sh [REPOSITORY]   (default: this checkout)
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

if ! command -v clang-format >/dev/null; then
  echo "check-format: clang-format is not installed (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
mapfile -t files < <(git ls-files '*.cpp' '*.h' | grep -v '^shaders/')
if [ ${#files[@]} -eq 0 ]; then
  echo "check-format: no C++ files found (run from a git checkout)" >&2
  exit 1
fi
unformatted=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || unformatted+=("$f")
done
if [ ${#unformatted[@]} -gt 0 ]; then
  printf '%s: not as clang-format lays it out\n' "${unformatted[@]}" >&2
  echo "check-format: ${#unformatted[@]} of ${#files[@]} files differ; run clang-format -i on them" >&2
  exit 1
fi
echo "check-format: ${#files[@]} files as clang-format lays them out ($(clang-format --version | sed 's/.*version \([0-9.]*\).*/\1/'))"
