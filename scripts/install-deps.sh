#!/usr/bin/env bash
# Installs pedesis' build and test dependencies from Debian's packages.
# Idempotent: packages already present are not touched, so `make` stays fast.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  googletest libgtest-dev
  nlohmann-json3-dev libtomlplusplus-dev libcli11-dev libfmt-dev librandom123-dev
  libomp-dev python3-numpy python3-gsd python3-scipy
  libcairo2-dev ffmpeg python3-matplotlib
  python3-dev pybind11-dev python3-pytest
  python3-ase python3-vtk9 zlib1g-dev
  python3-nbclient python3-ipykernel python3-nbconvert python3-nbformat
  python3-venv python3-build python3-pybind11
  clang
  libopenmpi-dev openmpi-bin
  libcpp-httplib-dev libssl-dev chromium
)
# Node.js and npm build the viewer page (web/viewer); a machine that has them from
# elsewhere (NodeSource) keeps them: Debian's npm would conflict with that nodejs.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq || echo "install-deps: apt-get update failed; trying the cached package lists"
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
