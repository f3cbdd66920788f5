#!/usr/bin/env bash
# vkray as an installed tool. Builds (a fresh build folder with the tests off,
# or the build folder given: scripts/install-check.sh build), installs it into
# a temporary prefix P, makes P read-only, and from another temporary folder
# runs the installed P/bin/vkray, which must find its shaders and stress cases
# in P/share/vkray and write nothing into P (its SPIR-V cache goes to the
# user's cache folder). Then packages it (cpack -G DEB) and checks the .deb's
# contents and Depends, without installing it. Any failed step stops it with
# "install-check: FAIL: ..." and that step's output.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh

tmp=$(mktemp -d)
trap 'chmod -R u+w "$tmp" 2>/dev/null || true; rm -rf "$tmp"' EXIT

fail() {
  echo "install-check: FAIL: $*" >&2
  exit 1
}
# step NAME COMMAND...: runs it, prints its output when it fails.
step() {
  local name=$1 status=0
  shift
  echo "install-check: $name"
  "$@" >"$tmp/step.log" 2>&1 || status=$?
  if [ "$status" -ne 0 ]; then
    cat "$tmp/step.log" >&2
    fail "$name: exit status $status ($*)"
  fi
  tail -n 1 "$tmp/step.log" | sed 's/^/  /'
}

if [ $# -ge 1 ]; then
  [ -f "$1/CMakeCache.txt" ] || fail "$1 is not a configured build folder"
  build=$(cd "$1" && pwd)
else
  build="$tmp/build"
  step "configure a fresh build folder (tests off)" \
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVKRAY_TESTS=OFF
fi
step "build $build" cmake --build "$build"

prefix="$tmp/prefix"
step "cmake --install into $prefix" cmake --install "$build" --prefix "$prefix"
for f in bin/vkray share/vkray/shaders/trace.comp share/vkray/stress/tiny_sphere.sdl \
         share/vkray/scenes/default.sdl share/vkray/scenes/data/texels.png; do
  [ -e "$prefix/$f" ] || fail "cmake --install left no $prefix/$f"
done
[ "$(ls "$prefix/bin")" = vkray ] || fail "$prefix/bin holds more than vkray: $(ls "$prefix/bin")"
# Read-only for every user (root writes anyway, so the listing is compared too).
chmod -R a+rX,a-w "$prefix"
find "$prefix" -printf '%P %s %T@\n' | sort >"$tmp/prefix-before"

# From an unrelated folder, with a home of its own: the SPIR-V cache must go to
# $HOME/.cache/vkray (spirv_cache.cpp), not beside the binary.
work="$tmp/work" home="$tmp/home"
mkdir -p "$work" "$home"
cd "$work"
export HOME="$home" LP_NUM_THREADS=2
unset VKRAY_CACHE_DIR XDG_CACHE_HOME
vkray="$prefix/bin/vkray"
step "installed vkray render" "$vkray" render "$prefix/share/vkray/scenes/default.sdl" -o out.png --size 64x48
[ -s out.png ] || fail "installed vkray render wrote no $work/out.png"
step "installed vkray stress" "$vkray" stress --cases tiny_sphere --size 32x24 --out R
for f in stress.csv stress.json stress.html; do
  [ -s "R/$f" ] || fail "installed vkray stress wrote no $work/R/$f"
done
step "installed vkray shaders check" "$vkray" shaders check
ls "$home/.cache/vkray/"*.spv >/dev/null 2>&1 || fail "no SPIR-V cache in $home/.cache/vkray"
find "$prefix" -printf '%P %s %T@\n' | sort >"$tmp/prefix-after"
diff "$tmp/prefix-before" "$tmp/prefix-after" >&2 ||
  fail "the installed vkray wrote into its prefix $prefix (changes above)"
cd - >/dev/null

# The .deb, built into the temporary folder and only looked at.
step "cpack -G DEB" cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/deb"
deb=$(ls "$tmp"/deb/vkray_*.deb 2>/dev/null | head -n 1)
[ -n "$deb" ] || fail "cpack -G DEB wrote no vkray_*.deb into $tmp/deb"
dpkg-deb -c "$deb" >"$tmp/deb-contents" || fail "dpkg-deb -c $deb"
for f in ./usr/bin/vkray ./usr/share/vkray/shaders/trace.comp ./usr/share/vkray/stress/tiny_sphere.sdl \
         ./usr/share/vkray/scenes/default.sdl; do
  awk '{print $NF}' "$tmp/deb-contents" | grep -qx -- "$f" || fail "$(basename "$deb") lacks $f"
done
depends=$(dpkg-deb -f "$deb" Depends)
case "$depends" in
  *"mesa-vulkan-drivers | vulkan-icd"*) ;;
  *) fail "$(basename "$deb") Depends lacks 'mesa-vulkan-drivers | vulkan-icd': $depends" ;;
esac
case "$depends" in
  *libvulkan1*) ;;
  *) fail "$(basename "$deb") Depends lacks libvulkan1: $depends" ;;
esac
case "$depends" in  # dpkg-shlibdeps' find: the binary links OpenEXR (.exr output)
  *libopenexr*) ;;
  *) fail "$(basename "$deb") Depends lacks OpenEXR's library (libopenexr-3-1-30): $depends" ;;
esac
echo "install-check: $(basename "$deb"): Depends: $depends"
echo "install-check: ok"
