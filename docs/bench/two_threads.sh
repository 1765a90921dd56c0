#!/usr/bin/env bash
# Two threads against one: `pedesis bench` with --threads 2 over --threads 1, in
# alternated pairs, on a machine whose cores may be shared with other jobs.
#
#   docs/bench/two_threads.sh [PAIRS] [-- BENCH-ARGS...]
#
#   PAIRS       pairs to run (default 8)
#   BENCH-ARGS  passed to `pedesis bench abp` (default: --n 36000 --steps 1000
#               --warmup 100, the ABP tutorial's system); in.lj is
#               `-- --model lj --n 32000 --steps 500 --warmup 50`
#   PEDESIS     the binary (default build/pedesis of this checkout)
#
# Each pair runs one thread, then two, and reads each run's rate over its timed window
# (particle_steps_per_second). On a host shared with other jobs one core is often slowed
# by a neighbour for seconds at a time, which a run on two threads feels and a run on one
# may not. So each core's speed is probed just before and just after every pair (a
# one-thread run of 4,000 particles pinned to it with taskset, about 0.3 s), and a pair
# counts as quiet when its four probes all ran at 95% or more of that core's fastest probe
# of the sitting. The script prints every pair with its probes, then the median and range
# of the ratios over all pairs and over the quiet ones.
set -euo pipefail
prog=two_threads.sh
repo_root=$(cd "$(dirname -- "${BASH_SOURCE[0]}")/../.." && pwd -P)
# shellcheck source=bench_common.sh
source "$repo_root/docs/bench/bench_common.sh"

pairs=8
if [[ $# -gt 0 && $1 != -- ]]; then
    if ! is_uint "$1" || (($1 == 0)); then die "PAIRS must be a positive whole number, not '$1'"; fi
    pairs=$1
    shift
fi
if [[ $# -gt 0 ]]; then
    [[ $1 == -- ]] || die "unexpected argument '$1' (bench arguments follow --)"
    shift
fi
bench_args=("$@")
((${#bench_args[@]})) || bench_args=(--n 36000 --steps 1000 --warmup 100)
bin=${PEDESIS:-$repo_root/build/pedesis}
[[ -x $bin ]] || die "no pedesis binary at $bin (build it, or set PEDESIS)"
command -v taskset > /dev/null || die "taskset (util-linux) is needed to probe each core"
(($(nproc) >= 2)) || die "two threads need two cores; this machine has $(nproc)"

# rate THREADS ARGS...: particle-steps per second of one bench run
rate() {
    local threads=$1
    shift
    local out
    out=$(OMP_NUM_THREADS=$threads "$bin" bench abp "$@" --threads "$threads" 2>&1) ||
        die "pedesis bench failed: $out"
    awk '/^particle_steps_per_second:/ { print $2; found = 1 } END { exit !found }' <<< "$out" ||
        die "no particle_steps_per_second in: $out"
}
probe() { taskset -c "$1" bash -c "$(declare -f rate die); bin='$bin'; prog='$prog'; rate 1 --n 4000 --steps 1500 --warmup 20"; }

note "$pairs pairs of $bin bench abp ${bench_args[*]} (one thread, then two)"
rows=()
for ((p = 1; p <= pairs; ++p)); do
    a0=$(probe 0)
    a1=$(probe 1)
    r1=$(rate 1 "${bench_args[@]}")
    r2=$(rate 2 "${bench_args[@]}")
    b0=$(probe 0)
    b1=$(probe 1)
    rows+=("$r1 $r2 $a0 $a1 $b0 $b1")
done

printf '%s\n' "${rows[@]}" | awk '
    { for (i = 1; i <= 6; ++i) v[NR, i] = $i
      b0 = ($3 > $5 ? $3 : $5); b1 = ($4 > $6 ? $4 : $6)
      if (b0 > best0) best0 = b0
      if (b1 > best1) best1 = b1 }
    function med(a, n,   i, j, t) {
        for (i = 2; i <= n; ++i) for (j = i; j > 1 && a[j - 1] > a[j]; --j) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
        return (n % 2) ? a[(n + 1) / 2] : 0.5 * (a[n / 2] + a[n / 2 + 1])
    }
    END {
        for (k = 1; k <= NR; ++k) {
            r = v[k, 2] / v[k, 1]
            lo0 = (v[k, 3] < v[k, 5] ? v[k, 3] : v[k, 5]) / best0
            lo1 = (v[k, 4] < v[k, 6] ? v[k, 4] : v[k, 6]) / best1
            quiet = lo0 >= 0.95 && lo1 >= 0.95
            all[++na] = r
            if (quiet) q[++nq] = r
            printf "pair %d: %.3f  (one thread %.2f, two %.2f million particle-steps/s; probes core 0 %.2f %.2f, core 1 %.2f %.2f)%s\n",
                k, r, v[k, 1] / 1e6, v[k, 2] / 1e6, v[k, 3] / best0, v[k, 5] / best0,
                v[k, 4] / best1, v[k, 6] / best1, quiet ? "  quiet" : ""
        }
        lo = hi = all[1]; for (k = 1; k <= na; ++k) { if (all[k] < lo) lo = all[k]; if (all[k] > hi) hi = all[k] }
        printf "all pairs (%d): median %.3f, range %.3f-%.3f\n", na, med(all, na), lo, hi
        if (nq == 0) { print "quiet pairs: none"; exit }
        lo = hi = q[1]; for (k = 1; k <= nq; ++k) { if (q[k] < lo) lo = q[k]; if (q[k] > hi) hi = q[k] }
        printf "quiet pairs (%d): median %.3f, range %.3f-%.3f\n", nq, med(q, nq), lo, hi
    }'
