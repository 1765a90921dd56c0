#!/usr/bin/env bash
# The GPU check of issue 32, as one prepared script: on a machine with an NVIDIA GPU,
# CUDA's nvcc, CMake and a C++ compiler, but none of Debian's -dev packages and no
# network, it builds the GPU path, runs the `gpu` tests and the GPU benchmarks, and prints
# what docs/gpu.md reports. The libraries the build needs beyond CUDA travel in
# .gpu-deps/ (scripts/gpu_deps.sh makes it on Debian). Figures go to stdout and, where
# $OUT is set, to $OUT/gpu_check.log.
#
#   scripts/gpu_deps.sh            # here, once
#   scripts/gpu_check.sh [quick]   # there ("quick": tests, and the benchmark at 10^6 only)
set -uo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
deps=$root/.gpu-deps
build=${BUILD_GPU:-$root/build-gpu}
log=${OUT:+$OUT/gpu_check.log}
log=${log:-/dev/null}
mode=${1:-full}
exec > >(tee -a "$log") 2>&1
t0=$(date +%s)
stage() { echo; echo "== $(( $(date +%s) - t0 )) s: $*"; }

stage "machine"
nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.memory --format=csv,noheader || true
grep -m1 "model name" /proc/cpuinfo
nproc
nvcc --version | tail -2
cmake --version | head -1
${CXX:-g++} --version | head -1
[ -d "$deps/usr/include" ] || { echo "gpu_check: $deps is missing: run scripts/gpu_deps.sh first"; exit 2; }

stage "configure"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
zlib=$deps/usr/lib/x86_64-linux-gnu/libz.so
[ -e "$zlib" ] || zlib=$deps/lib/x86_64-linux-gnu/libz.so.1
mkdir -p "$build"
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DPEDESIS_CUDA=ON -DPEDESIS_CUDA_ARCHITECTURES="${CUDA_ARCHITECTURES:-90}" \
  -DPEDESIS_GRAPHICS=OFF -DPEDESIS_PYTHON_MODULE=OFF -DPEDESIS_MPI=OFF \
  -DCMAKE_PREFIX_PATH="$deps/usr" -DRANDOM123_INCLUDE_DIR="$deps/usr/include" \
  -DZLIB_INCLUDE_DIR="$deps/usr/include" -DZLIB_LIBRARY="$zlib" \
  -DGTEST_ROOT="$deps/usr" -DCMAKE_BUILD_RPATH="$deps/usr/lib/x86_64-linux-gnu;$deps/lib/x86_64-linux-gnu" \
  >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
grep "pedesis:" "$build/configure.log"

stage "build"
cmake --build "$build" -j "$(nproc)" --target pedesis gpu_engine_test gpu_host_test cli_device_test \
  >"$build/build.log" 2>&1 || { tail -60 "$build/build.log"; exit 1; }
echo "built"

stage "tests (label gpu, and the host side)"
(cd "$build" && ctest --output-on-failure -L gpu --timeout 300)
tests_gpu=$?
(cd "$build" && ctest --output-on-failure -R "GpuModel|GpuStepper|DeviceChoice" --timeout 120)
tests_host=$?

bench() { echo; echo "\$ pedesis bench abp $*"; OMP_NUM_THREADS=1 "$build/pedesis" bench abp "$@"; }
stage "benchmark: 2D ABP of the tutorial (density 0.4, dt 0.01), GPU"
sizes=(100000 1000000 10000000)
[ "$mode" = quick ] && sizes=(1000000)
for n in "${sizes[@]}"; do
  steps=1000; [ "$n" -ge 10000000 ] && steps=300
  bench --device gpu --n "$n" --steps "$steps" --warmup 50 | grep -E "^(bench|device|wall|list|particle_steps|device_bytes)"
done
stage "benchmark: the same on one CPU core of this machine"
bench --n 1000000 --steps 60 --warmup 5 | grep -E "^(bench|wall|particle_steps|bytes)"
stage "benchmark: 3D LJ at in.lj's state (NVE, dt 0.005, skin 0.3), GPU"
for n in "${sizes[@]}"; do
  steps=1000; [ "$n" -ge 10000000 ] && steps=200
  bench --model lj --device gpu --n "$n" --steps "$steps" --warmup 50 | grep -E "^(bench|device|wall|list|particle_steps|device_bytes)"
done
if [ "$mode" != quick ] && command -v ncu >/dev/null; then
  stage "DRAM traffic of one step's kernels (ncu), 2D ABP and LJ at 10^6"
  for model in abp lj; do
    timeout 120 ncu --metrics dram__bytes_read.sum,dram__bytes_write.sum,gpu__time_duration.sum \
      --launch-skip 100 --launch-count 16 --csv \
      "$build/pedesis" bench abp --model "$model" --device gpu --n 1000000 --steps 60 --warmup 20 \
      2>/dev/null | grep -E '"(dram__|gpu__time)' | awk -F'","' '{print $5, $(NF-2), $(NF-1), $NF}' | head -48
  done
fi
stage "done: gpu tests exit $tests_gpu, host tests exit $tests_host"
[ $tests_gpu -eq 0 ] && [ $tests_host -eq 0 ]
