#!/usr/bin/env bash
# Runs every libFuzzer target of a `make fuzz` build for SECONDS each (or, with RUNS set in
# the environment, for exactly that many inputs from seed 1: the same inputs every time,
# which is what CI runs), from the seed corpus
# in fuzz/corpus/<target>/ (new inputs go to a scratch copy, the repository's corpus is
# not touched). Exit 1 if any target finds a crash, a leak, a sanitizer report or a
# timeout; the input that did it is left as crash-*/timeout-* in the build's fuzz-out/.
#   scripts/run-fuzzers.sh BUILD_DIR SECONDS
set -euo pipefail
build=${1:?build directory}
seconds=${2:-60}
root=$(cd "$(dirname "$0")/.." && pwd)
out="$build/fuzz-out"
mkdir -p "$out"
status=0
for target in fuzz_config fuzz_tutorial_json fuzz_xyz fuzz_gsd fuzz_checkpoint fuzz_sweep; do
  corpus="$out/$target-corpus"
  rm -rf "$corpus" && mkdir -p "$corpus"
  cp "$root/fuzz/corpus/$target/"* "$corpus/"
  echo "fuzz: $target for ${RUNS:+$RUNS inputs}${RUNS:-${seconds}s}"
  if [ -n "${RUNS:-}" ]; then budget=(-runs="$RUNS" -seed=1); else budget=(-max_total_time="$seconds"); fi
  if ! (cd "$out" && ASAN_OPTIONS=detect_leaks=1 "$build/fuzz/$target" "$corpus" \
          "${budget[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
          -print_final_stats=1 2> "$target.log"); then
    echo "fuzz: $target FAILED; see $out/$target.log"
    tail -40 "$out/$target.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$out/$target.log" | tail -2
  fi
done
exit $status
