#!/usr/bin/env bash
# Installs the Debian (bookworm) packages vkray needs to build, test and run.
# Quick when they are already there: apt is only called for what is missing.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-tools vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools
  libglm-dev libstb-dev
  zlib1g-dev  # deflate for the PNGs stb_image_write encodes (a quarter of stb's own time)
  libassimp-dev  # mesh FILE in OBJ, PLY, glTF 2.0, STL, OFF, ... (host/scene/mesh_import.*)
  assimp-testmodels  # real model files by others, which the tests render (tests/scene/mesh_import_test.cpp)
  libopenexr-dev  # OpenEXR 3: -o X.exr, --aov X.exr and compare reading .exr
  openexr  # its tools (exrheader): the tests check that they list vkray's layers
  libgtest-dev
  clang libclang-rt-dev  # scripts/fuzz.sh: clang and its libFuzzer/sanitizer runtimes
  libopenmpi-dev openmpi-bin  # rendering across MPI ranks (docs/mpi.md)
  libboost-dev  # Boost.Multiprecision: the stress oracle's 113-bit float128 (host/numerics/oracle.*)
  dpkg-dev file  # cpack -G DEB: dpkg-shlibdeps finds the .deb's library dependencies
  libglfw3-dev  # vkray view: the window and its Vulkan surface
  xvfb xauth libx11-dev  # vkray view's tests: a virtual X server, and Xlib to look into it
  libcli11-dev  # the command lines of vkray and vkray_bench: subcommands, ranges, generated --help
  nlohmann-json3-dev  # the JSON that reports write, and that the tests read back
  clang-format  # scripts/check-format.sh: CI checks the C++ against .clang-format
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "vkray: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
$sudo apt-get update
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
