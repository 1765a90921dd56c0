#!/usr/bin/env bash
# Unpacks the Debian packages that the GPU build needs beyond CUDA, CMake and a C++
# compiler into .gpu-deps/ (ignored by git), so that scripts/gpu_check.sh builds on a GPU
# machine that has none of them and no network. Run it here, on Debian, once; it
# downloads with apt-get (no root needed for `apt-get download`).
set -euo pipefail
cd "$(dirname "$0")/.."
out=.gpu-deps
packages=(
  nlohmann-json3-dev libtomlplusplus-dev libtomlplusplus3 libcli11-dev libfmt-dev libfmt9
  librandom123-dev zlib1g-dev zlib1g libgtest-dev
)
rm -rf "$out" && mkdir -p "$out/debs"
(cd "$out/debs" && apt-get download "${packages[@]}" >/dev/null)
for deb in "$out"/debs/*.deb; do dpkg-deb -x "$deb" "$out"; done
rm -rf "$out/debs" "$out/usr/share/doc" "$out/usr/share/man"
echo "gpu_deps: ${packages[*]} unpacked into $out ($(du -sh "$out" | cut -f1))"
