#!/usr/bin/env bash
# Side-by-side benchmark: pedesis's event-driven engine against Smallenburg's EDMD
# (F. Smallenburg, "Efficient event-driven simulations of hard spheres",
#  Eur. Phys. J. E 45, 22 (2022); https://github.com/FSmallenburg/EDMD, MIT licence).
#
# None of the peer's code is part of pedesis or of this repository. This script only
# reads an already fetched copy of it, patches a COPY in a scratch directory, builds
# that copy there and deletes it afterwards.
#
# How the peer was obtained (2026-11-23):
#   repository  FSmallenburg/EDMD, commit 2d0c86293f7ff1ca4674681ff9e1eefa3797377e
#               ("link fix", 2026-05-04; last code change c118bbc, 2024-12-09)
#   fetched as a bare git directory, then exported outside the repository with
#     mkdir -p /work/peers/edmd
#     git --git-dir=<bare repo> archive HEAD | tar -x -C /work/peers/edmd
#   variant used: Single/ (one event scheduled per particle, neighbour lists with a
#   1.5 sigma shell, bucket calendar + sorted tree) -- the paper's fastest code.
#   Git blob ids of the files used at that commit (checked below, warning on mismatch):
#     Single/mdSingle.c   e58851bca75a384d94d894e3195867ca170a3056
#     Single/mdSingle.h   f97fbe4e6762e908711fc75b1263bb1028a868ca
#     Single/mt19937ar.c  27127662d807f3cfc4f7a0faf8a773da8891aca4
#     Single/Makefile     3906365f41833383463d3b2079ca725b2067f0e7
#
# What is patched (sed, on the scratch copy of Single/mdSingle.c only; every edit is
# checked afterwards and the script stops if an anchor was not found). All of these are
# the run parameters the peer keeps as globals at the top of its file, plus timing and
# output; no physics, neighbour-list, or calendar code is touched:
#   line 22   double maxtime = 100;      -> WARMUP + TIME        (run from t = 0 to 22)
#   line 23   int makesnapshots = 0;     -> 0                    (already 0; enforced)
#   line 27   int initialconfig = 0;     -> 1                    (FCC start, no input file)
#             (with SIZE_RATIO < 1: left at 0, and the script writes the start file
#             init.sph in the peer's own text format: the rock-salt mixture that
#             `pedesis bench event --size-ratio` builds, same positions and radii)
#   line 29   double packfrac = 0.25;    -> ETA (0.45)
#   line 30   int N = 4000;              -> 4 n^3 nearest to N   (32000 = 4*20^3,
#                                                                  1000188 = 4*63^3)
#   line 77   const int usethermostat = 1; -> EDMD_THERMOSTAT (default 0; see below)
#   line 9    #define MAXNEIGH 24        -> 48, only with SIZE_RATIO < 1 (a large sphere
#             among small ones has more than 24 partners in its 1.5-contact shell, and
#             the peer stops with "Too many neighbors. Increase MAXNEIGH.")
#   line 1    #include <time.h> added (clock_gettime)
#   lines 88-92 (main): before the peer's own loop "while (simtime <= maxtime) step();"
#             an untimed loop "while (simtime <= WARMUP) step();" is inserted, then
#             clock_gettime(CLOCK_MONOTONIC) and the collision counter are read; after
#             the peer's loop both are read again and the script prints
#             "edmd_window: ... collisions C wall_seconds S" and
#             "collisions_per_second: R" (the peer's own `colcounter`, i.e. valid pair
#             collisions, counted over the window t = WARMUP .. WARMUP + TIME).
#             Same window and same definition as `pedesis bench event`.
#   line 95   outputsnapshot();  (final snapshot_end.sph)  -> removed
#   lines 1110-1114 (write): the five lines writing press.n*.sph -> commented out.
#             The peer's once-per-time-unit screen line (energy, pressure) is kept.
#
# Thermostat: Single/mdSingle.c ships with `usethermostat = 1` (every 0.01 time units it
# redraws the velocities of N/100 random particles), although its README says the
# thermostat is off by default, Cell/ and Multi/ ship with 0, and the paper's benchmarks
# are microcanonical. `pedesis bench event` is microcanonical, so the default here is
# EDMD_THERMOSTAT=0 (as in docs/performance.md's earlier comparison). Set
# EDMD_THERMOSTAT=1 to run the peer exactly as shipped.
#
# Build: the peer's own, unmodified Single/Makefile, i.e.
#   gcc -Wall -Ofast -funroll-loops -march=native mdSingle.c -o md -lm
# (pedesis is whatever build/pedesis is; the script prints its CMAKE_BUILD_TYPE and
# flags from build/CMakeCache.txt when present).
#
# Usage:
#   docs/bench/edmd_side_by_side.sh [EDMD_SRC]
# Environment (defaults in brackets):
#   EDMD_SRC         fetched peer tree containing Single/          [/work/peers/edmd]
#   N                particles; the peer gets the nearest 4 n^3     [32000]
#                    (N=1000000 -> peer 1000188, pedesis 1000000)
#   PAIRS            alternations (peer, then pedesis)              [6]
#   ETA              packing fraction                               [0.45]
#   SIZE_RATIO       < 1: equimolar binary mixture, diameters 1 and SIZE_RATIO, in the
#                    rock-salt arrangement (N must be 8 k^3, e.g. 32768); the peer's
#                    Single/ reads it as its start file (its neighbour shell is 1.5 times
#                    each pair's contact distance, its cells sized by the largest)  [1]
#   WARMUP, TIME     untimed warm-up, then timed window (sim time)  [2, 20]
#   EDMD_THERMOSTAT  peer's thermostat on (1) or off (0)            [0]
#   PEDESIS          pedesis binary                                 [<repo>/build/pedesis]
#   SCRATCH          scratch directory (created if missing)         [mktemp -d]
#   KEEP_SCRATCH     1 = keep the scratch directory (patched source, logs, patch.diff)
#   SHOW_PATCH       1 = print the unified diff of the patch
#   RESULTS          optional path: copy the per-run TSV there
# Example (smoke test, seconds):  N=4000 PAIRS=1 TIME=1 WARMUP=0.5 docs/bench/edmd_side_by_side.sh
# Both codes run single-threaded (OMP_NUM_THREADS=1); each process is wrapped in
# /usr/bin/time -v for its CPU time (user + sys, whole process including setup) and
# maximum resident set size. Compare the per-pair ratios, not absolute rates, on a
# shared machine.

set -euo pipefail

prog=edmd_side_by_side

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_root=$(cd "$script_dir/../.." && pwd)
# shellcheck source=bench_common.sh
source "$script_dir/bench_common.sh"

EDMD_SRC=${1:-${EDMD_SRC:-/work/peers/edmd}}
N=${N:-32000}
PAIRS=${PAIRS:-6}
ETA=${ETA:-0.45}
WARMUP=${WARMUP:-2}
TIME=${TIME:-20}
EDMD_THERMOSTAT=${EDMD_THERMOSTAT:-0}
SIZE_RATIO=${SIZE_RATIO:-1}
PEDESIS=${PEDESIS:-$repo_root/build/pedesis}
SCRATCH=${SCRATCH:-}
KEEP_SCRATCH=${KEEP_SCRATCH:-0}
SHOW_PATCH=${SHOW_PATCH:-0}
RESULTS=${RESULTS:-}

# ---------------------------------------------------------------- checks
is_uint "$N" && ((10#$N >= 4)) || die "N must be an integer >= 4 (got '$N')"
is_uint "$PAIRS" && ((10#$PAIRS >= 1)) || die "PAIRS must be a positive integer (got '$PAIRS')"
N=$((10#$N))
PAIRS=$((10#$PAIRS))
is_num "$ETA" || die "ETA must be a number (got '$ETA')"
is_num "$WARMUP" || die "WARMUP must be a number (got '$WARMUP')"
is_num "$TIME" || die "TIME must be a positive number (got '$TIME')"
awk -v t="$TIME" 'BEGIN { exit !(t > 0) }' || die "TIME must be > 0 (got '$TIME')"
[[ $EDMD_THERMOSTAT == 0 || $EDMD_THERMOSTAT == 1 ]] ||
    die "EDMD_THERMOSTAT must be 0 or 1 (got '$EDMD_THERMOSTAT')"

for tool in gcc make awk sed sort diff; do
    command -v "$tool" >/dev/null || die "'$tool' not found in PATH"
done
[[ -x /usr/bin/time ]] || die "/usr/bin/time (GNU time, for CPU time and max RSS) not found; apt-get install time"
[[ -d $EDMD_SRC/Single ]] ||
    die "no Single/ under EDMD_SRC=$EDMD_SRC; fetch FSmallenburg/EDMD and export it there (see the header of this script)"
for f in mdSingle.c mdSingle.h mt19937ar.c Makefile; do
    [[ -f $EDMD_SRC/Single/$f ]] || die "missing $EDMD_SRC/Single/$f"
done
[[ -x $PEDESIS ]] || die "pedesis binary not found or not executable: $PEDESIS (build it first, or set PEDESIS)"
"$PEDESIS" bench event --help >/dev/null 2>&1 || die "$PEDESIS has no working 'bench event' subcommand"

is_num "$SIZE_RATIO" && awk -v r="$SIZE_RATIO" 'BEGIN { exit !(r > 0 && r <= 1) }' ||
    die "SIZE_RATIO must lie in (0, 1] (got '$SIZE_RATIO')"
mixture=$(awk -v r="$SIZE_RATIO" 'BEGIN { print (r < 1) ? 1 : 0 }')

# Peer: nearest N = 4 n^3 (its FCC routine insists on a perfect cube of unit cells);
# a mixture has exactly N = 8 k^3 in both codes.
if [[ $mixture == 1 ]]; then
    ncell=$(awk -v n="$N" 'BEGIN { c = int(exp(log(n / 8) / 3) + 0.5); print c }')
    ((8 * ncell * ncell * ncell == N)) || die "SIZE_RATIO < 1 needs N = 8 k^3 (e.g. 32768), not $N"
    NPEER=$N
    INITIALCONFIG=0
    MAXNEIGH=48
else
    ncell=$(awk -v n="$N" 'BEGIN { c = int(exp(log(n / 4) / 3) + 0.5); if (c < 1) c = 1; print c }')
    NPEER=$((4 * ncell * ncell * ncell))
    INITIALCONFIG=1
    MAXNEIGH=24
fi
MAXTIME=$(awk -v w="$WARMUP" -v t="$TIME" 'BEGIN { printf "%.10g", w + t }')

# ---------------------------------------------------------------- scratch
scratch_entries=(Single logs)
make_scratch edmd_bench

peer="$SCRATCH/Single"
rm -rf -- "$peer" "$SCRATCH/logs"
cp -R -- "$EDMD_SRC/Single" "$peer"
rm -f -- "$peer/md"
mkdir -p "$SCRATCH/logs"
logs="$SCRATCH/logs"

# Provenance: the blob ids at commit 2d0c862 (see header).
declare -A expected_blob=(
    [mdSingle.c]=e58851bca75a384d94d894e3195867ca170a3056
    [mdSingle.h]=f97fbe4e6762e908711fc75b1263bb1028a868ca
    [mt19937ar.c]=27127662d807f3cfc4f7a0faf8a773da8891aca4
    [Makefile]=3906365f41833383463d3b2079ca725b2067f0e7
)
if command -v git >/dev/null; then
    for f in "${!expected_blob[@]}"; do
        got=$(git hash-object "$peer/$f")
        [[ $got == "${expected_blob[$f]}" ]] ||
            note "WARNING: Single/$f differs from FSmallenburg/EDMD@2d0c862 (blob $got); results may not be comparable"
    done
fi

# ---------------------------------------------------------------- patch
src="$peer/mdSingle.c"
cp -- "$src" "$peer/mdSingle.c.orig"
cat >"$SCRATCH/bench.sed" <<EOF
1i #include <time.h>
s/^double maxtime = [-+0-9.eE]*;/double maxtime = $MAXTIME;/
s/^int makesnapshots = [0-9]*;/int makesnapshots = 0;/
s/^int initialconfig = [0-9]*;/int initialconfig = $INITIALCONFIG;/
s/^double packfrac = [-+0-9.eE]*;/double packfrac = $ETA;/
s/^int N = [0-9]*;/int N = $NPEER;/
s/^#define MAXNEIGH [0-9]*\$/#define MAXNEIGH $MAXNEIGH/
s/^const int usethermostat = [0-9]*;/const int usethermostat = $EDMD_THERMOSTAT;/
/^    while (simtime <= maxtime)\$/i\\
    /* bench: untimed warm-up, then time the window up to maxtime */\\
    while (simtime <= $WARMUP) step();\\
    unsigned int bench_c0 = colcounter;\\
    double bench_s0 = simtime;\\
    struct timespec bench_t0, bench_t1;\\
    clock_gettime(CLOCK_MONOTONIC, &bench_t0);
/^    simtime = maxtime;\$/i\\
    clock_gettime(CLOCK_MONOTONIC, &bench_t1);\\
    {\\
        double bench_s = (double)(bench_t1.tv_sec - bench_t0.tv_sec) + 1e-9 * (double)(bench_t1.tv_nsec - bench_t0.tv_nsec);\\
        unsigned int bench_c = colcounter - bench_c0;\\
        printf("edmd_window: N %d eta %g t %.6f .. %.6f collisions %u wall_seconds %.3f\\\\n", N, packfrac, bench_s0, simtime, bench_c, bench_s);\\
        printf("collisions_per_second: %.0f\\\\n", bench_c / bench_s);\\
        fflush(stdout);\\
    }
s|^    outputsnapshot();\$|    /* bench: no final snapshot */|
/sprintf(filename, "press\\.n/,/fclose(file);/s|^|//bench: no press file // |
EOF
sed -i -f "$SCRATCH/bench.sed" "$src"

check() { # pattern count message
    local got
    got=$(grep -c -E -- "$1" "$src" || true)
    [[ $got == "$2" ]] || die "patch check failed ($3): expected $2 line(s) matching '$1', found $got"
}
check '^#include <time\.h>$' 1 "time.h"
check "^double maxtime = $MAXTIME;" 1 "maxtime"
check '^int makesnapshots = 0;' 1 "makesnapshots"
check "^int initialconfig = $INITIALCONFIG;" 1 "initialconfig"
check "^double packfrac = $ETA;" 1 "packfrac"
check "^int N = $NPEER;" 1 "N"
check "^#define MAXNEIGH $MAXNEIGH\$" 1 "MAXNEIGH"
check "^const int usethermostat = $EDMD_THERMOSTAT;" 1 "usethermostat"
check 'clock_gettime\(CLOCK_MONOTONIC, &bench_t0\)' 1 "timer start"
check 'clock_gettime\(CLOCK_MONOTONIC, &bench_t1\)' 1 "timer stop"
check '^ *outputsnapshot\(\);' 0 "final snapshot call"
check '^//bench: no press file ' 5 "press file"
check '^//bench: no press file .*fopen' 2 "press file fopen"
diff -u "$peer/mdSingle.c.orig" "$src" >"$SCRATCH/patch.diff" || true
added=$(grep -c '^+[^+]' "$SCRATCH/patch.diff" || true)
removed=$(grep -c '^-[^-]' "$SCRATCH/patch.diff" || true)
note "patched scratch copy: +$added/-$removed lines (diff in $SCRATCH/patch.diff)"
[[ $SHOW_PATCH == 1 ]] && cat "$SCRATCH/patch.diff" >&2

# The mixture's start in the peer's text format (N; box; "type x y z radius" per
# particle, box from 0 to L): large spheres (diameter 1) on an FCC lattice of k^3
# cells, each with a small one half a cell edge along x, as pedesis bench event does
# (there the box runs from -L/2 to L/2).
if [[ $mixture == 1 ]]; then
    awk -v n="$N" -v k="$ncell" -v r="$SIZE_RATIO" -v eta="$ETA" 'BEGIN {
        pi = 3.14159265358979323846
        L = exp(log(n * 0.5 * (pi / 6) * (1 + r * r * r) / eta) / 3)
        a = L / k
        if (a < 1 + r) { print "no room for the rock-salt start at this ETA" > "/dev/stderr"; exit 1 }
        split("0 0.5 0.5 0", bx, " "); split("0 0.5 0 0.5", by, " "); split("0 0 0.5 0.5", bz, " ")
        printf "%d\n%.17g %.17g %.17g\n", n, L, L, L
        for (x = 0; x < k; x++) for (y = 0; y < k; y++) for (z = 0; z < k; z++)
            for (b = 1; b <= 4; b++) for (s = 0; s < 2; s++)
                printf "%c %.17g %.17g %.17g %.17g\n", (s ? "b" : "a"),
                    (x + bx[b] + 0.5 * s + 0.25) * a, (y + by[b] + 0.25) * a,
                    (z + bz[b] + 0.25) * a, s ? 0.5 * r : 0.5
    }' >"$peer/init.sph" || die "could not write the mixture start"
fi

# ---------------------------------------------------------------- build
note "building the peer with its own Makefile in $peer"
make -C "$peer" >"$logs/build.log" 2>&1 || { cat "$logs/build.log" >&2; die "peer build failed"; }
[[ -x $peer/md ]] || die "peer build produced no 'md' binary"
peer_cc=$(grep -E '^gcc|^cc|mdSingle\.c -o md' "$logs/build.log" | head -1 || true)

# ---------------------------------------------------------------- header
describe_pedesis "$PEDESIS"
echo "== EDMD (FSmallenburg/EDMD Single) vs pedesis bench event"
echo "cpu:       ${cpu:-unknown}  ($(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg))"
echo "peer:      $EDMD_SRC/Single, N $NPEER ($([[ $mixture == 1 ]] && echo 8 || echo 4)*${ncell}^3), thermostat $EDMD_THERMOSTAT"
echo "peer cc:   ${peer_cc:-see $logs/build.log}"
echo "pedesis:   $PEDESIS @ $ped_rev$ped_dirty${ped_flags:+, $ped_flags}, N $N"
[[ $mixture == 1 ]] && echo "mixture:   equimolar, diameters 1 and $SIZE_RATIO, rock-salt start (peer: init.sph)"
echo "system:    eta $ETA, 3D, warm-up t = 0..$WARMUP untimed, window t = $WARMUP..$MAXTIME timed, $PAIRS pair(s)"
[[ $N == "$NPEER" ]] || echo "note:      peer N differs from pedesis N (the peer needs 4 n^3); rates are per collision, RSS per own N"
echo

# ---------------------------------------------------------------- runs
# run_one label log timefile cmd...   -> prints "rate cpu_s maxrss_kb collisions"
field() { awk -v k="$1" 'index($0, k) == 1 { sub(k, ""); gsub(/^[ \t]+/, ""); print; exit }' "$2"; }
run_one() {
    local label=$1 log=$2 tf=$3
    shift 3
    if ! OMP_NUM_THREADS=1 /usr/bin/time -v -o "$tf" "$@" >"$log" 2>&1; then
        tail -n 20 "$log" >&2
        die "$label run failed (log above; full log in $log, kept with KEEP_SCRATCH=1)"
    fi
    local rate user sys rss
    rate=$(field "collisions_per_second:" "$log")
    [[ -n $rate ]] || { tail -n 20 "$log" >&2; die "$label printed no collisions_per_second line"; }
    user=$(time_field "User time \\(seconds\\)" "$tf")
    sys=$(time_field "System time \\(seconds\\)" "$tf")
    rss=$(time_field "Maximum resident set size \\(kbytes\\)" "$tf")
    [[ -n $user && -n $sys && -n $rss ]] || die "could not read /usr/bin/time output $tf"
    echo "$rate $(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }') $rss"
}

tsv="$SCRATCH/results.tsv"
printf 'pair\tcode\tn\tcollisions_per_second\twindow_collisions\tcpu_s\tmaxrss_kb\n' >"$tsv"
printf '%-4s %14s %14s %8s %9s %9s %9s %9s\n' pair "peer coll/s" "pedesis coll/s" ratio \
    "peer cpu" "ped cpu" "peer B/p" "ped B/p"
for ((i = 1; i <= PAIRS; i++)); do
    # command substitution (not a pipe) so that a failed run stops the script
    out=$(cd "$peer" && run_one "peer (pair $i)" "$logs/peer.$i.log" "$logs/peer.$i.time" ./md)
    read -r pr pc pm <<<"$out"
    pcoll=$(awk '/^edmd_window:/ { for (k = 1; k < NF; k++) if ($k == "collisions") print $(k + 1) }' "$logs/peer.$i.log")
    out=$(cd "$SCRATCH" && run_one "pedesis (pair $i)" "$logs/pedesis.$i.log" "$logs/pedesis.$i.time" \
        "$PEDESIS" bench event --dim 3 --n "$N" --eta "$ETA" --time "$TIME" --warmup "$WARMUP" \
        --size-ratio "$SIZE_RATIO")
    read -r qr qc qm <<<"$out"
    qcoll=$(awk '/^collisions:/ { print $2; exit }' "$logs/pedesis.$i.log")
    printf '%s\tpeer\t%s\t%s\t%s\t%s\t%s\n' "$i" "$NPEER" "$pr" "${pcoll:-}" "$pc" "$pm" >>"$tsv"
    printf '%s\tpedesis\t%s\t%s\t%s\t%s\t%s\n' "$i" "$N" "$qr" "${qcoll:-}" "$qc" "$qm" >>"$tsv"
    awk -v i="$i" -v pr="$pr" -v qr="$qr" -v pc="$pc" -v qc="$qc" -v pm="$pm" -v qm="$qm" \
        -v np="$NPEER" -v nq="$N" 'BEGIN {
        printf "%-4s %14.0f %14.0f %8.3f %9.2f %9.2f %9.0f %9.0f\n",
            i, pr, qr, qr / pr, pc, qc, pm * 1024 / np, qm * 1024 / nq }'
done

# ---------------------------------------------------------------- summary
col() { awk -F'\t' -v c="$1" -v k="$2" 'NR > 1 && $2 == c { print $k }' "$tsv"; }
ratios=$(awk -F'\t' 'NR > 1 { if ($2 == "peer") p[$1] = $4; else q[$1] = $4 } END { for (i in p) print q[i] / p[i] }' "$tsv")
r_med=$(median <<<"$ratios")
r_min=$(sort -g <<<"$ratios" | head -1)
r_max=$(sort -g <<<"$ratios" | tail -1)
echo
printf 'pedesis/peer collisions per second: median of %d per-pair ratios %.3f (range %.3f - %.3f)\n' \
    "$PAIRS" "$r_med" "$r_min" "$r_max"
printf '%-8s %8s %16s %18s %12s %16s\n' code N "median coll/s" "median window coll" "median cpu s" "median RSS B/part"
for c in peer pedesis; do
    n=$([[ $c == peer ]] && echo "$NPEER" || echo "$N")
    printf '%-8s %8s %16.0f %18.0f %12.2f %16.0f\n' "$c" "$n" \
        "$(col "$c" 4 | median)" "$(col "$c" 5 | median)" "$(col "$c" 6 | median)" \
        "$(awk -v k="$(col "$c" 7 | median)" -v n="$n" 'BEGIN { print k * 1024 / n }')"
done
echo "(cpu s: user + sys of the whole process, setup and warm-up included; RSS: maximum resident set size / N)"
if [[ -n $RESULTS ]]; then
    cp -- "$tsv" "$RESULTS"
    note "per-run results written to $RESULTS"
fi
