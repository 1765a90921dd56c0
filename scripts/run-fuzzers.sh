#!/usr/bin/env bash
# Runs every libFuzzer target of a `make fuzz` build for SECONDS each (or, with RUNS set in
# the environment, for exactly that many inputs from seed 1: the same inputs every time,
# which is what CI runs; fuzz_run and fuzz_view_request, whose every input is a whole
# simulation or two connections to a server, get a quarter of them), from the seed corpus
# in fuzz/corpus/<target>/ (new inputs go to a scratch
# copy, the repository's corpus is not touched). JOBS targets run side by side (default:
# the number of cores; each is single-threaded). Exit 1 if any target finds a crash, a
# leak, a sanitizer report or a timeout; the input that did it is left as
# crash-*/timeout-* in the build's fuzz-out/.
#   scripts/run-fuzzers.sh BUILD_DIR SECONDS
set -euo pipefail
build=${1:?build directory}
seconds=${2:-60}
jobs=${JOBS:-$(nproc)}
root=$(cd "$(dirname "$0")/.." && pwd)
out="$build/fuzz-out"
mkdir -p "$out"

# One target, its log in $out/TARGET.log and its verdict in $out/TARGET.status.
run_target() {
  local target=$1 corpus="$out/$1-corpus" budget schedule=()
  rm -rf "$corpus" && mkdir -p "$corpus"
  cp "$root/fuzz/corpus/$target/"* "$corpus/"
  if [ -n "${RUNS:-}" ]; then
    local runs=$RUNS
    # (each input of these is a whole run, or two connections to a server)
    case $target in fuzz_run | fuzz_view_request) runs=$((RUNS / 4)) ;; esac
    budget=(-runs="$runs" -seed=1)
  else
    budget=(-max_total_time="$seconds")
  fi
  # Each input of fuzz_run (a whole run) reaches tens of thousands of coverage features,
  # and the entropic schedule's bookkeeping over them cost four times the runs themselves
  # (measured: 24 inputs/s with it, 107 without, at the same coverage).
  if [ "$target" = fuzz_run ]; then schedule=(-entropic=0); fi
  echo "fuzz: $target ${budget[*]}"
  if (cd "$out" && ASAN_OPTIONS=detect_leaks=1 "$build/fuzz/$target" "$corpus" \
        "${budget[@]}" ${schedule[@]+"${schedule[@]}"} -timeout=10 -rss_limit_mb=2048 \
        -max_len=65536 -print_final_stats=1 2> "$target.log"); then
    echo ok > "$out/$target.status"
  else
    echo failed > "$out/$target.status"
  fi
}

targets=(fuzz_checkpoint fuzz_run fuzz_config fuzz_tutorial_json fuzz_xyz fuzz_gsd fuzz_sweep fuzz_resume)
# the viewer's server, in builds that have it (PEDESIS_GRAPHICS)
if [ -x "$build/fuzz/fuzz_view_request" ]; then targets=(fuzz_view_request "${targets[@]}"); fi
# the longest first, so that the two cores finish together
running=0
for target in "${targets[@]}"; do
  rm -f "$out/$target.status"
  run_target "$target" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait

status=0
for target in "${targets[@]}"; do
  if [ "$(cat "$out/$target.status" 2>/dev/null)" != ok ]; then
    echo "fuzz: $target FAILED; see $out/$target.log"
    tail -40 "$out/$target.log"
    status=1
  else
    echo "fuzz: $target"
    grep -E "stat::number_of_executed_units|cov:" "$out/$target.log" | tail -2
  fi
done
exit $status
