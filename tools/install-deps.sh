#!/usr/bin/env bash
# Installs the Debian 12 packages deepgi needs; skips the ones already present (idempotent).
set -euo pipefail
# openimageio-tools: Debian's OIIO CMake config checks that /usr/bin/iconvert etc. exist, and only that package has them.
# fonts-dejavu-core: the font the bench's plots and grids are labelled with (OIIO render_text, bench/draw.cpp);
# draco gltfpack: draco_transcoder and gltfpack, other producers of Draco and meshopt files for the tests; xvfb xauth: the viewer tests; clang libclang-rt-14-dev: tools/fuzz.sh; libegl-dev: `--context egl`.
PKGS=(build-essential cmake pkg-config
  libglfw3-dev libglm-dev libimgui-dev libstb-dev libtinygltf-dev libtinyobjloader-dev libdraco-dev libmeshoptimizer-dev draco gltfpack
  nlohmann-json3-dev libcli11-dev
  libopenimageio-dev openimageio-tools libosmesa6-dev libegl-dev python3-glad libembree-dev libgtest-dev fonts-dejavu-core
  xvfb xauth clang libclang-rt-14-dev)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "deepgi: all ${#PKGS[@]} system packages present"
  exit 0
fi
echo "deepgi: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "deepgi: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
