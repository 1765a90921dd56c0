#!/usr/bin/env bash
# Side-by-side benchmark: pedesis's soft/active engine (`pedesis run`, dynamics
# "langevin", "nve", "brownian") against LAMMPS, one thread each, at equal physics and
# from the same initial configuration, on four systems:
#
#   wca2d  2D WCA disks, N = 36,000, number density 0.4, Langevin T = 1, gamma = 1,
#          dt = 0.005, skin 0.3            lammps_wca2d.in     pedesis_wca2d.toml
#   wca3d  3D WCA (2^(1/6) cut, shifted) at in.lj's state point: fcc rho = 0.8442,
#          32,000 atoms, T = 1.44 start, NVE, dt = 0.005, skin 0.3
#                                          lammps_wca3d.in     pedesis_wca3d.toml
#   lj3d   LAMMPS' bench/in.lj: LJ cut at 2.5 (not shifted), same start, NVE,
#          dt = 0.005, skin 0.3            lammps_lj3d.in      pedesis_lj3d.toml
#   abp    the ABP tutorial's system of `pedesis bench abp` (no alignment), N = 36,000:
#          harmonic k = 10, a = 2, alpha = 1, Brownian T = 0.1, gamma_t = gamma_r = 1,
#          dt = 0.01, skin 1.0             lammps_abp_side.in  pedesis_abp.toml
#                                          (physics lines of lammps_abp.in)
#
# Same start: for each system LAMMPS builds the start (create_atoms on a lattice, or at
# random for abp; velocity create; dipole/random) and writes it with write_data; the
# data file is converted to pedesis' tutorial-JSON initial file by
# lammps_data_to_json.py (standard library only, every double kept exactly); LAMMPS's
# timed input then read_data's the same file. This is redone in the scratch directory
# at every invocation.
#
# None of LAMMPS is part of pedesis or of this repository. The two LAMMPS binaries:
#   LMP (systems wca2d, wca3d, lj3d; default `lmp`): Debian 12's package,
#       `apt-get install lammps`, version 20220106.git7586adbb6a+ds1-2+b2, i.e. LAMMPS
#       "29 Sep 2021 - Update 2" (stable): an MPI (Open MPI 4.1.4) build with shared
#       liblammps, built by Debian's standard CMake packaging (g++ 12.2 with
#       dpkg-buildflags' -g -O2, no -march). Run here as a plain serial process: `lmp -nocite -log none -in ...`
#       (no mpirun: one MPI rank; no -sf/-pk suffix: the plain, non-OPENMP styles).
#   LMP_BROWNIAN (system abp; default /work/peers/lammps-build/lmp): Debian's lmp lacks
#       the BROWNIAN package (fix brownian/sphere, fix propel/self), so the same Debian
#       source package was built outside the repository (2026-11-23):
#         echo 'deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian bookworm main' \
#             > /etc/apt/sources.list.d/debsrc.list
#         apt-get update
#         mkdir -p /work/peers/lammps-src && cd /work/peers/lammps-src && apt-get source lammps
#             # lammps 20220106.git7586adbb6a+ds1-2, Debian's patches applied
#         mkdir -p /work/peers/lammps-build && cd /work/peers/lammps-build
#         cmake ../lammps-src/lammps-20220106.git7586adbb6a+ds1/cmake -D PKG_BROWNIAN=on \
#             -D PKG_DIPOLE=on -D BUILD_MPI=off -D BUILD_OMP=off -D CMAKE_BUILD_TYPE=Release \
#             -D CMAKE_DISABLE_FIND_PACKAGE_MPI=ON
#         nice -n 19 make -j1
#       (CMAKE_DISABLE_FIND_PACKAGE_MPI only because CMake's FindMPI fails hard on this
#       machine's incomplete Open MPI development files; the build is serial either way.)
#       That is a static, serial build with g++ 12.2 and CMake's Release flags
#       -O3 -DNDEBUG (no -march), packages BROWNIAN and DIPOLE only. It runs systems
#       wca2d..lj3d too: LMP=/work/peers/lammps-build/lmp compares pedesis with an -O3
#       LAMMPS there as well.
#
# Timed windows (both wall-clock, both after an untimed warm-up of WARMUP steps):
#   LAMMPS: the input runs `run WARMUP` then `run STEPS`; the rate is
#       STEPS * N / X from the second "Loop time of X on 1 procs for STEPS steps with N
#       atoms" line. LAMMPS's Loop time excludes each run's setup (list build and the
#       first force evaluation) and includes the thermo output of the last step.
#   pedesis: `pedesis run` has no warm-up option. Its summary.json gives wall_seconds,
#       the wall time of the invocation's steps (from after the set-up: reading the
#       config and initial file, the first list build and forces, the step-0 log row and
#       frame; to the end, including the log row of the last step, the final frame,
#       which writes nothing here as formats = [], and the final checkpoint.bin, about
#       5-6 MB for these systems and a few ms: one step of wca3d plus the checkpoint
#       and log row took 8 ms), and particle_steps_per_second = steps of this
#       invocation * N / wall_seconds. The warm-up is excluded with pedesis's exact
#       restart: a first invocation runs steps 0..WARMUP and writes checkpoint.bin; the
#       timed invocation continues it with --restart to WARMUP + STEPS, bit for bit the
#       trajectory of one uninterrupted run, and its summary.json rate is the one
#       reported (checked against STEPS * N / wall_seconds). WARMUP=0: one invocation.
# Whole-process figures from /usr/bin/time -v: CPU time (user + sys, set-up, I/O and
#   warm-up included) and maximum RSS per particle. For pedesis they are the sum (CPU)
#   and the larger (RSS) of its two invocations; the first parses the ~5 MB JSON initial
#   file (a JSON document in memory: about 1 KB per particle, most of pedesis's maximum
#   RSS here), the timed one reads only the checkpoint (its config gets [box] and
#   [[species]] from the converter, so the JSON file is not read again) and its own RSS
#   is reported too ("timed B/p"; maxrss_timed_kb in results.tsv). Fixed costs weigh at
#   N of a few 10^4: `lmp -h` alone takes 28 MB (Debian's lmp loads Open MPI; the own
#   build is static and serial), a tiny pedesis run 8.5 MB.
#   Both codes run with OMP_NUM_THREADS=1.
#
# Equal physics, and where it is only equal in distribution:
#   * same positions and velocities (and directors = dipoles for abp) at step 0, same
#     potentials (lj/cut 2^(1/6) with pair_modify shift yes = pedesis "wca"; lj/cut 2.5
#     = pedesis "lj" with cutoff 2.5, both unshifted, no tail correction), masses 1;
#   * NVE (wca3d, lj3d): velocity Verlet in both; the trajectories are the same to
#     rounding for the first tens of steps, then diverge (chaos); thermodynamics agree;
#   * Langevin (wca2d): LAMMPS fix nve + fix langevin (damp 1 = m / gamma, uniform
#     noise of the right variance, its own generator); pedesis BAOAB with Gaussian
#     Philox noise (its default), or with PEDESIS_NOISE=uniform uniform Philox noise of
#     the same variance, LAMMPS's kind: equal in distribution, O(dt) differences in the
#     integrator;
#   * abp: LAMMPS fix brownian/sphere (rng gaussian) + propel/self dipole + the harmonic
#     force tabulated (pair_style table linear 2000); pedesis brownian +
#     brownian_rotation + harmonic (exact) + self_propulsion: equal in distribution.
#     LAMMPS interpolates its table internally in r^2 (f/r linear in r^2), which
#     overstates the force of pairs closer than about 0.03 (93 instead of 20 at
#     r = 0.005); the random start (create_atoms random, as lammps_abp.in, with no
#     minimum distance) has a few such pairs, the warmed-up state hardly any;
#   * temperature: LAMMPS uses d N - d degrees of freedom, pedesis d N for langevin and
#     d (N - 1) for nve: a relative difference of 1/N in wca2d;
#   * neighbour lists: skin as stated; LAMMPS rebuilds when any particle has moved
#     skin/2 (`neigh_modify every 1 delay 0 check yes`), pedesis when a pair within the
#     cutoff could be missing (docs/engines.md, "Neighbour list"), except lj3d where
#     LAMMPS keeps in.lj's `neigh_modify delay 0 every 20 check no` (rebuild every 20
#     steps, unchecked) unless LJ_LAMMPS_NEIGH=check; pedesis always checks. LAMMPS uses
#     a half list (newton on), pedesis too (a coloured sweep); LAMMPS sorts atoms every 1000 steps
#     (default), pedesis every 500 (default sort_every).
#   The script prints each code's final temperature, potential energy per particle,
#   pressure and its virial part, medians over the pairs (abp: pressures other than the
#   virial part differ by definition; there is no temperature).
#
# Usage:
#   docs/bench/lammps_side_by_side.sh
# Environment (defaults in brackets):
#   SYSTEMS        subset of "wca2d wca3d lj3d abp", in this order  [all four]
#   PAIRS          alternations per system (LAMMPS, then pedesis)   [6]
#   STEPS          timed steps                                      [1000]
#   WARMUP         untimed steps before them                        [100]
#   PEDESIS        pedesis binary                                   [<repo>/build/pedesis]
#   LMP            LAMMPS for wca2d, wca3d, lj3d                    [lmp]
#   LMP_BROWNIAN   LAMMPS with BROWNIAN and DIPOLE, for abp         [/work/peers/lammps-build/lmp]
#   LJ_LAMMPS_NEIGH  lj3d's LAMMPS list rule: inlj (every 20, no check) or check  [inlj]
#   PEDESIS_NOISE  gaussian, or uniform: pedesis's brownian and langevin get
#                  uniform_noise = true (wca2d, abp), the noise LAMMPS' fix langevin
#                  draws (and fix brownian with rng uniform): equal physics  [gaussian]
#   SCRATCH        scratch directory outside the repository (created; its
#                  per-system subdirectories are replaced)          [mktemp -d]
#   KEEP_SCRATCH   1 = keep the scratch directory (data, JSON, configs, logs)
#   RESULTS        optional path: copy the per-run TSV there
# Example (smoke test, a minute):  PAIRS=1 STEPS=50 WARMUP=10 docs/bench/lammps_side_by_side.sh
# Compare the per-pair ratios, not absolute rates, on a shared machine.

set -euo pipefail

prog=lammps_side_by_side

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_root=$(cd "$script_dir/../.." && pwd -P)
# shellcheck source=bench_common.sh
source "$script_dir/bench_common.sh"

SYSTEMS=${SYSTEMS:-"wca2d wca3d lj3d abp"}
PAIRS=${PAIRS:-6}
STEPS=${STEPS:-1000}
WARMUP=${WARMUP:-100}
PEDESIS=${PEDESIS:-$repo_root/build/pedesis}
LMP=${LMP:-lmp}
LMP_BROWNIAN=${LMP_BROWNIAN:-/work/peers/lammps-build/lmp}
LJ_LAMMPS_NEIGH=${LJ_LAMMPS_NEIGH:-inlj}
PEDESIS_NOISE=${PEDESIS_NOISE:-gaussian}
SCRATCH=${SCRATCH:-}
KEEP_SCRATCH=${KEEP_SCRATCH:-0}
RESULTS=${RESULTS:-}
PYTHON=/usr/bin/python3

# ---------------------------------------------------------------- systems
# name: LAMMPS input, pedesis config, dimension, converter style, converter options,
# binary variable, extra LAMMPS variables, description
declare -A S_IN S_TOML S_DIM S_STYLE S_CONV S_LMPVAR S_VARS S_DESC
S_IN[wca2d]=lammps_wca2d.in;    S_TOML[wca2d]=pedesis_wca2d.toml; S_DIM[wca2d]=2
S_STYLE[wca2d]=atomic;          S_CONV[wca2d]="--radius 0.5";      S_LMPVAR[wca2d]=LMP
S_VARS[wca2d]="";               S_DESC[wca2d]="2D WCA disks, rho 0.4, Langevin T 1 gamma 1, dt 0.005, skin 0.3"
S_IN[wca3d]=lammps_wca3d.in;    S_TOML[wca3d]=pedesis_wca3d.toml; S_DIM[wca3d]=3
S_STYLE[wca3d]=atomic;          S_CONV[wca3d]="--radius 0.5";      S_LMPVAR[wca3d]=LMP
S_VARS[wca3d]="";               S_DESC[wca3d]="3D WCA, fcc rho 0.8442, T0 1.44, NVE, dt 0.005, skin 0.3"
S_IN[lj3d]=lammps_lj3d.in;      S_TOML[lj3d]=pedesis_lj3d.toml;   S_DIM[lj3d]=3
S_STYLE[lj3d]=atomic;           S_CONV[lj3d]="--radius 0.5";       S_LMPVAR[lj3d]=LMP
S_VARS[lj3d]="-var neigh $LJ_LAMMPS_NEIGH"
S_DESC[lj3d]="3D LJ rc 2.5 (in.lj), fcc rho 0.8442, T0 1.44, NVE, dt 0.005, skin 0.3"
S_IN[abp]=lammps_abp_side.in;   S_TOML[abp]=pedesis_abp.toml;     S_DIM[abp]=2
S_STYLE[abp]=sphere-dipole;     S_CONV[abp]="";                    S_LMPVAR[abp]=LMP_BROWNIAN
S_VARS[abp]="";                 S_DESC[abp]="2D ABP, rho 0.4, harmonic k 10, alpha 1, T 0.1, dt 0.01, skin 1.0"

# ---------------------------------------------------------------- checks
is_uint "$PAIRS" && ((10#$PAIRS >= 1)) || die "PAIRS must be a positive integer (got '$PAIRS')"
is_uint "$STEPS" && ((10#$STEPS >= 1)) || die "STEPS must be a positive integer (got '$STEPS')"
is_uint "$WARMUP" || die "WARMUP must be a non-negative integer (got '$WARMUP')"
PAIRS=$((10#$PAIRS))
STEPS=$((10#$STEPS))
WARMUP=$((10#$WARMUP))
TOTAL=$((WARMUP + STEPS))
[[ $LJ_LAMMPS_NEIGH == inlj || $LJ_LAMMPS_NEIGH == check ]] ||
    die "LJ_LAMMPS_NEIGH must be inlj or check (got '$LJ_LAMMPS_NEIGH')"
[[ $PEDESIS_NOISE == gaussian || $PEDESIS_NOISE == uniform ]] ||
    die "PEDESIS_NOISE must be gaussian or uniform (got '$PEDESIS_NOISE')"
read -r -a systems <<<"$SYSTEMS"
((${#systems[@]} >= 1)) || die "SYSTEMS is empty"
for s in "${systems[@]}"; do
    [[ -n ${S_IN[$s]:-} ]] || die "unknown system '$s' in SYSTEMS (known: wca2d wca3d lj3d abp)"
done

for tool in awk sed sort grep; do
    command -v "$tool" >/dev/null || die "'$tool' not found in PATH"
done
[[ -x /usr/bin/time ]] || die "/usr/bin/time (GNU time, for CPU time and max RSS) not found; apt-get install time"
[[ -x $PYTHON ]] || die "$PYTHON not found (the data-file converter needs it)"
[[ -x $PEDESIS ]] || die "pedesis binary not found or not executable: $PEDESIS (build it first, or set PEDESIS)"
for s in "${systems[@]}"; do
    for f in "${S_IN[$s]}" "${S_TOML[$s]}"; do
        [[ -f $script_dir/$f ]] || die "missing $script_dir/$f"
    done
done
[[ -f $script_dir/lammps_data_to_json.py ]] || die "missing $script_dir/lammps_data_to_json.py"

# every LAMMPS binary in use, and the styles its systems need
lmp_path() { # variable name -> resolved path
    local v=${!1}
    command -v "$v" 2>/dev/null || true
}
declare -A LMP_OK
for s in "${systems[@]}"; do
    var=${S_LMPVAR[$s]}
    [[ -n ${LMP_OK[$var]:-} ]] && continue
    bin=$(lmp_path "$var")
    [[ -n $bin && -x $bin ]] || {
        if [[ $var == LMP_BROWNIAN ]]; then
            die "LMP_BROWNIAN=${!var} not found: system abp needs a LAMMPS built with the BROWNIAN and DIPOLE packages (see the header of this script for how), or leave abp out of SYSTEMS"
        fi
        die "$var=${!var} not found (apt-get install lammps, or set $var)"
    }
    help=$("$bin" -h 2>/dev/null || true)
    grep -q 'Large-scale Atomic/Molecular' <<<"$help" || die "$var=$bin does not look like LAMMPS (lmp -h)"
    LMP_OK[$var]=$bin
done
need_style() { # system style... ; checks the binary's style list
    local s=$1 bin=${LMP_OK[${S_LMPVAR[$1]}]} help st
    shift
    help=$("$bin" -h 2>/dev/null)
    for st in "$@"; do
        grep -qw -- "$st" <<<"$help" ||
            die "${S_LMPVAR[$s]}=$bin has no '$st' style, needed by system $s"
    done
}
for s in "${systems[@]}"; do
    case $s in
        wca2d) need_style "$s" lj/cut langevin enforce2d nve ;;
        wca3d | lj3d) need_style "$s" lj/cut nve ;;
        abp) need_style "$s" brownian/sphere propel/self dipole table enforce2d ;;
    esac
done

# ---------------------------------------------------------------- scratch
scratch_entries=("${systems[@]}" results.tsv)
make_scratch lammps_side

# ---------------------------------------------------------------- header
describe_pedesis "$PEDESIS"
lmp_desc() {
    local bin=$1 ver deb="" c
    ver=$("$bin" -h 2>/dev/null | sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p' | head -1)
    if [[ $bin == /usr/bin/* ]] && command -v dpkg-query >/dev/null; then
        deb=$(dpkg-query -W -f='Debian lammps ${Version}' lammps 2>/dev/null || true)
    fi
    c="$(dirname "$bin")/CMakeCache.txt"
    if [[ -f $c ]]; then
        local bt fl
        bt=$(sed -n 's/^CMAKE_BUILD_TYPE:STRING=//p' "$c")
        fl=$(sed -n "s/^CMAKE_CXX_FLAGS_${bt^^}:STRING=//p" "$c" 2>/dev/null || true)
        deb="own build, $bt${fl:+ ($fl)}"
    fi
    echo "$bin: LAMMPS ${ver:-?}${deb:+, $deb}"
}
echo "== LAMMPS vs pedesis run, one thread each"
echo "cpu:       ${cpu:-unknown}  ($(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg))"
for var in "${!LMP_OK[@]}"; do
    printf '%-10s %s\n' "$var:" "$(lmp_desc "${LMP_OK[$var]}")"
done
echo "pedesis:   $PEDESIS @ $ped_rev$ped_dirty${ped_flags:+, $ped_flags}"
echo "runs:      systems: ${systems[*]}; $PAIRS pair(s) each (LAMMPS, then pedesis); $WARMUP untimed + $STEPS timed steps; pedesis noise: $PEDESIS_NOISE"
echo "           rates: particle-steps per wall second of each code's own timed window; cpu: user + sys"
echo "           of the whole process(es); RSS: maximum resident set size / N"
echo

# ---------------------------------------------------------------- helpers
cpu_rss() { # timefile -> "cpu_s rss_kb"
    local user sys rss
    user=$(time_field "User time \\(seconds\\)" "$1")
    sys=$(time_field "System time \\(seconds\\)" "$1")
    rss=$(time_field "Maximum resident set size \\(kbytes\\)" "$1")
    [[ -n $user && -n $sys && -n $rss ]] || die "could not read /usr/bin/time output $1"
    awk -v u="$user" -v s="$sys" -v r="$rss" 'BEGIN { printf "%.2f %d\n", u + s, r }'
}
timed() { # label log timefile cmd...   (in the current directory)
    local label=$1 log=$2 tf=$3
    shift 3
    if ! OMP_NUM_THREADS=1 /usr/bin/time -v -o "$tf" "$@" >"$log" 2>&1; then
        tail -n 20 "$log" >&2
        die "$label failed (log above; full log in $log, kept with KEEP_SCRATCH=1)"
    fi
}
jkey() { # key summary.json -> value
    awk -v k="\"$1\":" '$1 == k { v = $2; sub(/,$/, "", v); print v; exit }' "$2"
}
csv_last() { # column log.csv -> value in the last row ("" if no such column)
    awk -F, -v c="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i; next }
        { last = $0 } END { if (!k) exit; n = split(last, f, ","); print f[k] }' "$2"
}
set_key() { # file key value: replace the one line "key = ..." (checked)
    local n
    n=$(grep -c "^$2 = " "$1" || true)
    [[ $n == 1 ]] || die "$1: expected one '$2 = ' line, found $n"
    sed -i "s|^$2 = .*|$2 = $3|" "$1"
}
fmt_or_dash() { if [[ -z $1 || $1 == nan ]]; then echo "-"; else printf "$2" "$1"; fi; }

tsv="$SCRATCH/results.tsv"
printf 'system\tpair\tcode\tn\tsteps\twindow_s\tparticle_steps_per_second\tlist_builds\tcpu_s\tmaxrss_kb\ttemperature\tpe_per_particle\tpressure\tpressure_virial\tmaxrss_timed_kb\n' >"$tsv"
col() { # system code column-number -> values
    awk -F'\t' -v s="$1" -v c="$2" -v k="$3" 'NR > 1 && $1 == s && $3 == c && $k != "" { print $k }' "$tsv"
}
summary_lines=()

# ---------------------------------------------------------------- systems
for s in "${systems[@]}"; do
    dir="$SCRATCH/$s"
    rm -rf -- "$dir"
    mkdir -p "$dir/logs"
    logs="$dir/logs"
    bin=${LMP_OK[${S_LMPVAR[$s]}]}
    lin="$script_dir/${S_IN[$s]}"
    # shellcheck disable=SC2206
    extra=(${S_VARS[$s]})

    # the common start
    (cd "$dir" && "$bin" -nocite -log none -in "$lin" -var mode gen -var data start.data \
        >"$logs/gen.log" 2>&1) || { tail -n 20 "$logs/gen.log" >&2; die "$s: LAMMPS could not write the start"; }
    # shellcheck disable=SC2086
    "$PYTHON" "$script_dir/lammps_data_to_json.py" --dim "${S_DIM[$s]}" --style "${S_STYLE[$s]}" \
        ${S_CONV[$s]} --toml-tables "$dir/tables.toml" "$dir/start.data" "$dir/$s.json" \
        2>"$logs/convert.log" ||
        { cat "$logs/convert.log" >&2; die "$s: conversion of the data file failed"; }
    N=$(awk '$2 == "atoms" && NF == 2 { print $1; exit }' "$dir/start.data")
    is_uint "$N" || die "$s: no atom count in $dir/start.data"

    # pedesis configs: warm-up (0..WARMUP) and timed (WARMUP..TOTAL, restarted)
    cp -- "$script_dir/${S_TOML[$s]}" "$dir/timed.toml"
    set_key "$dir/timed.toml" file "\"$s.json\""
    set_key "$dir/timed.toml" steps "$TOTAL"
    set_key "$dir/timed.toml" log_every "$TOTAL"
    if [[ $PEDESIS_NOISE == uniform ]]; then
        # after the friction line of the brownian or langevin table (brownian_rotation
        # keeps Gaussian noise)
        awk '/^name = "(brownian|langevin)"/ { noisy = 1 } /^name = / && !/"(brownian|langevin)"/ { noisy = 0 }
             { print } noisy && /^gamma = / { print "uniform_noise = true"; noisy = 0; n++ }
             END { exit n == 1 ? 0 : 1 }' "$dir/timed.toml" >"$dir/timed.noise" ||
            die "$s: PEDESIS_NOISE=uniform needs one brownian or langevin [[integrator]]"
        mv -- "$dir/timed.noise" "$dir/timed.toml"
    fi
    if ((WARMUP > 0)); then
        cp -- "$dir/timed.toml" "$dir/warm.toml"
        set_key "$dir/warm.toml" steps "$WARMUP"
        set_key "$dir/warm.toml" log_every "$WARMUP"
        # the restarted, timed invocation gets [box] and [[species]], so that it does not
        # parse the JSON file again (the checkpoint has the state)
        cat -- "$dir/tables.toml" >>"$dir/timed.toml"
    fi

    echo "== $s: ${S_DESC[$s]}; N = $N"
    echo "   LAMMPS: $bin -nocite -log none -in ${S_IN[$s]}${S_VARS[$s]:+ ${S_VARS[$s]}}; pedesis: ${S_TOML[$s]}"
    printf '%-4s %13s %13s %7s %10s %10s %9s %9s\n' pair "LAMMPS Mps/s" "pedesis Mps/s" ratio \
        "LAMMPS cpu" "ped cpu" "LAMMPS B/p" "ped B/p"
    for ((i = 1; i <= PAIRS; i++)); do
        # ---- LAMMPS
        ll="$logs/lammps.$i.log"
        (cd "$dir" && timed "$s: LAMMPS (pair $i)" "$ll" "$logs/lammps.$i.time" \
            "$bin" -nocite -log none -in "$lin" -var data start.data \
            -var warmup "$WARMUP" -var steps "$STEPS" "${extra[@]}")
        read -r lt lsteps latoms < <(awk '/^Loop time of/ { t = $4; s = $9; n = $12 } END { print t, s, n }' "$ll")
        [[ $lsteps == "$STEPS" && $latoms == "$N" ]] ||
            die "$s: LAMMPS's last Loop time line is not for $STEPS steps with $N atoms (log $ll)"
        lbuilds=$(awk '/^Neighbor list builds =/ { b = $5 } END { print b }' "$ll")
        fin=$(grep '^side_final:' "$ll" | tail -1)
        [[ -n $fin ]] || die "$s: LAMMPS printed no side_final line (log $ll)"
        getf() { awk -v k="$1" '{ for (j = 1; j < NF; j++) if ($j == k) print $(j + 1) }' <<<"$fin"; }
        lrate=$(awk -v t="$lt" -v s="$STEPS" -v n="$N" 'BEGIN { printf "%.0f", s * n / t }')
        read -r lcpu lrss < <(cpu_rss "$logs/lammps.$i.time")
        lT=$(getf temp)
        lP=$(getf press)
        # abp: no temperature, and LAMMPS's total pressure counts dx/dt as a velocity;
        # only the virial part is comparable
        [[ $s == abp ]] && lT="" lP=""
        printf '%s\t%s\tlammps\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$s" "$i" "$N" "$STEPS" \
            "$lt" "$lrate" "$lbuilds" "$lcpu" "$lrss" "$lT" "$(getf pe)" "$lP" \
            "$(getf pvir)" "$lrss" >>"$tsv"

        # ---- pedesis
        rm -rf -- "$dir/warm" "$dir/timed"
        pcpu_w=0 prss_w=0 builds0=0
        if ((WARMUP > 0)); then
            (cd "$dir" && timed "$s: pedesis warm-up (pair $i)" "$logs/pedesis_warm.$i.log" \
                "$logs/pedesis_warm.$i.time" "$PEDESIS" run warm.toml --out warm)
            read -r pcpu_w prss_w < <(cpu_rss "$logs/pedesis_warm.$i.time")
            builds0=$(jkey list_rebuilds "$dir/warm/summary.json")
            (cd "$dir" && timed "$s: pedesis (pair $i)" "$logs/pedesis.$i.log" "$logs/pedesis.$i.time" \
                "$PEDESIS" run timed.toml --out timed --restart warm/checkpoint.bin)
        else
            (cd "$dir" && timed "$s: pedesis (pair $i)" "$logs/pedesis.$i.log" "$logs/pedesis.$i.time" \
                "$PEDESIS" run timed.toml --out timed)
        fi
        sj="$dir/timed/summary.json"
        [[ -f $sj ]] || die "$s: pedesis wrote no summary.json (log $logs/pedesis.$i.log)"
        pn=$(jkey particles "$sj")
        psteps=$(jkey steps "$sj")
        pwall=$(jkey wall_seconds "$sj")
        prate=$(jkey particle_steps_per_second "$sj")
        [[ $pn == "$N" && $psteps == "$TOTAL" ]] || die "$s: pedesis summary has N $pn, step $psteps (expected $N, $TOTAL)"
        awk -v r="$prate" -v w="$pwall" -v s="$STEPS" -v n="$N" \
            'BEGIN { x = s * n / w; exit !(r > 0 && (r - x) * (r - x) < 1e-6 * x * x) }' ||
            die "$s: pedesis particle_steps_per_second $prate is not STEPS * N / wall_seconds ($STEPS * $N / $pwall)"
        pbuilds=$(awk -v a="$(jkey list_rebuilds "$sj")" -v b="$builds0" 'BEGIN { print a - b }')
        read -r pcpu_t prss_t < <(cpu_rss "$logs/pedesis.$i.time")
        read -r pcpu prss < <(awk -v a="$pcpu_t" -v b="$pcpu_w" -v r="$prss_t" -v q="$prss_w" \
            'BEGIN { printf "%.2f %d\n", a + b, (r > q ? r : q) }')
        pl="$dir/timed/log.csv"
        ppe=$(awk -v u="$(csv_last potential_energy "$pl")" -v n="$N" 'BEGIN { printf "%.8g", u / n }')
        pT=$(csv_last temperature "$pl")
        pP=$(csv_last pressure "$pl")
        [[ $s == abp ]] && pP=""
        printf '%s\t%s\tpedesis\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$s" "$i" "$N" "$STEPS" \
            "$pwall" "$prate" "$pbuilds" "$pcpu" "$prss" "$pT" "$ppe" "$pP" \
            "$(csv_last pressure_virial "$pl")" "$prss_t" >>"$tsv"
        awk -v i="$i" -v lr="$lrate" -v pr="$prate" -v lc="$lcpu" -v pc="$pcpu" -v lm="$lrss" \
            -v pm="$prss" -v n="$N" 'BEGIN {
            printf "%-4s %13.3f %13.3f %7.3f %10.2f %10.2f %9.0f %9.0f\n",
                i, lr / 1e6, pr / 1e6, pr / lr, lc, pc, lm * 1024 / n, pm * 1024 / n }'
    done

    # ---- per-system summary
    ratios=$(awk -F'\t' -v s="$s" 'NR > 1 && $1 == s { if ($3 == "lammps") l[$2] = $7; else p[$2] = $7 }
        END { for (k in l) print p[k] / l[k] }' "$tsv")
    r_med=$(median <<<"$ratios")
    r_min=$(sort -g <<<"$ratios" | head -1)
    r_max=$(sort -g <<<"$ratios" | tail -1)
    printf 'pedesis/LAMMPS particle-steps per second: median of %d per-pair ratios %.3f (range %.3f - %.3f)\n' \
        "$PAIRS" "$r_med" "$r_min" "$r_max"
    printf '%-8s %12s %8s %10s %10s %7s %8s %12s %11s %11s\n' code "median Mps/s" "cpu s" "RSS B/p" \
        "timed B/p" builds T pe/N P P_virial
    for c in lammps pedesis; do
        m() { col "$s" "$c" "$1" | median; }
        printf '%-8s %12.3f %8.2f %10.0f %10.0f %7s %8s %12s %11s %11s\n' "$c" \
            "$(awk -v x="$(m 7)" 'BEGIN { print x / 1e6 }')" "$(m 9)" \
            "$(awk -v k="$(m 10)" -v n="$N" 'BEGIN { print k * 1024 / n }')" \
            "$(awk -v k="$(m 15)" -v n="$N" 'BEGIN { print k * 1024 / n }')" "$(m 8)" \
            "$(fmt_or_dash "$(m 11)" '%.4f')" "$(fmt_or_dash "$(m 12)" '%.6f')" \
            "$(fmt_or_dash "$(m 13)" '%.5f')" "$(fmt_or_dash "$(m 14)" '%.5f')"
    done
    echo "(medians over the pairs; timed B/p: RSS of the timed process only; builds: neighbour-list builds"
    echo " in the timed window; T, pe/N, P, P_virial: physics at step $TOTAL)"
    echo
    summary_lines+=("$(printf '%-6s %7s %9.3f %7.3f-%-7.3f %12.3f %13.3f %8.0f %8.0f %8.0f' "$s" "$N" \
        "$r_med" "$r_min" "$r_max" \
        "$(col "$s" lammps 7 | median | awk '{ print $1 / 1e6 }')" \
        "$(col "$s" pedesis 7 | median | awk '{ print $1 / 1e6 }')" \
        "$(col "$s" lammps 10 | median | awk -v n="$N" '{ print $1 * 1024 / n }')" \
        "$(col "$s" pedesis 10 | median | awk -v n="$N" '{ print $1 * 1024 / n }')" \
        "$(col "$s" pedesis 15 | median | awk -v n="$N" '{ print $1 * 1024 / n }')")")
done

# ---------------------------------------------------------------- summary
echo "== summary: pedesis / LAMMPS, particle-steps per wall second of each timed window ($STEPS steps after $WARMUP), $PAIRS pair(s)"
printf '%-6s %7s %9s %15s %12s %13s %8s %8s %8s\n' system N "median" "range" "LAMMPS Mps/s" \
    "pedesis Mps/s" "L B/p" "p B/p" "p tB/p"
for line in "${summary_lines[@]}"; do echo "$line"; done
echo "(Mps/s: million particle-steps per second; B/p: maximum RSS per particle; p tB/p: that of"
echo " pedesis's timed invocation alone; all medians over the pairs)"
if [[ -n $RESULTS ]]; then
    cp -- "$tsv" "$RESULTS"
    note "per-run results written to $RESULTS"
fi
