#!/usr/bin/env bash
# A newer lavapipe beside the system's, for Debian bookworm: Mesa from
# bookworm-backports (25.0), unpacked into DIR without touching the system's
# packages, its Vulkan driver file written to DIR/lvp_icd.json.
#
#   scripts/lavapipe-backports.sh DIR
#   eval "$(scripts/lavapipe-backports.sh ~/.local/share/vkray-mesa)"
#
# Prints the two variables that point the Vulkan loader at it (shell
# syntax, for eval); `vkray devices` then names the newer Mesa. vkray's
# kernel runs there about twice as fast as on bookworm's Mesa 22.3
# (BENCHMARKS.md, "A newer lavapipe"). The packages come from the Debian
# mirror this machine's apt already uses. To install it for the whole
# system instead: enable bookworm-backports, then
# `apt-get install -t bookworm-backports mesa-vulkan-drivers`.
set -euo pipefail

if [ $# -ne 1 ]; then
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
for tool in apt-get dpkg; do
  if ! command -v "$tool" >/dev/null; then
    echo "lavapipe-backports: $tool not found: this script is for Debian bookworm" >&2
    exit 1
  fi
done
mkdir -p "$1"
out=$(cd "$1" && pwd)

# The mirror that serves bookworm to this machine, with its backports suite
# (signed by the Debian archive keys apt already trusts).
mirror=$(apt-get indextargets --format '$(REPO_URI) $(RELEASE)' 2>/dev/null |
         awk '$2 == "bookworm" { print $1; exit }')
if [ -z "$mirror" ]; then
  echo "lavapipe-backports: apt has no source for Debian bookworm; on another release," \
       "install its newest mesa-vulkan-drivers instead" >&2
  exit 1
fi
apt_dir=$(mktemp -d)
trap 'rm -rf "$apt_dir"' EXIT
echo "deb ${mirror} bookworm-backports main" > "$apt_dir/sources.list"
mkdir -p "$apt_dir/lists/partial" "$apt_dir/debs"
apt_options=(-o "Dir::Etc::sourcelist=$apt_dir/sources.list" -o "Dir::Etc::sourceparts=-"
             -o "Dir::State::Lists=$apt_dir/lists" -o "APT::Get::List-Cleanup=0")
if ! apt-get "${apt_options[@]}" update >"$apt_dir/update.log" 2>&1; then
  cat "$apt_dir/update.log" >&2
  echo "lavapipe-backports: could not read bookworm-backports' package list" >&2
  exit 1
fi
# The driver, and the libdrm it needs (newer than bookworm's).
(cd "$apt_dir/debs" &&
 apt-get "${apt_options[@]}" download mesa-vulkan-drivers/bookworm-backports \
   libdrm2/bookworm-backports libdrm-amdgpu1/bookworm-backports >"$apt_dir/download.log" 2>&1) || {
  cat "$apt_dir/download.log" >&2
  echo "lavapipe-backports: could not download the packages" >&2
  exit 1
}
rm -rf "$out/root"
for deb in "$apt_dir"/debs/*.deb; do dpkg -x "$deb" "$out/root"; done
driver=$(find "$out/root" -name libvulkan_lvp.so | head -n 1)
if [ -z "$driver" ]; then
  echo "lavapipe-backports: the package held no libvulkan_lvp.so" >&2
  exit 1
fi
lib=$(dirname "$driver")
api=$(find "$out/root" -name 'lvp_icd*.json' -exec sed -n 's/.*"api_version": *"\([^"]*\)".*/\1/p' {} + |
      head -n 1)
cat > "$out/lvp_icd.json" <<EOF
{
    "file_format_version": "1.0.0",
    "ICD": {
        "library_path": "$driver",
        "api_version": "${api:-1.3.0}"
    }
}
EOF
echo "export VK_ICD_FILENAMES='$out/lvp_icd.json'"
echo "export LD_LIBRARY_PATH='$lib'\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
