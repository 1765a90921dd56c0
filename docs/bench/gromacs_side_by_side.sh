#!/usr/bin/env bash
# Side-by-side benchmark: pedesis's soft engine (`pedesis run`, dynamics "nve") against
# GROMACS on LAMMPS's bench/in.lj system, one thread each, from the same start.
#
# The peer: GROMACS 2022.5, Debian 12's source package gromacs 2022.5-2 (Debian's
# patches applied by `apt-get source`), built by this script's `build` mode outside the
# repository with the CPU's own SIMD kernels. None of GROMACS is part of pedesis or of
# this repository. What `build` does (root, for apt-get; GMX_SKIP_APT=1 skips 1-3):
#   1. /etc/apt/sources.list.d/pedesis-deb-src.sources (a private deb-src entry):
#        Types: deb-src, URIs: http://deb.debian.org/debian, Suites: bookworm,
#        Components: main, Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
#   2. apt-get update; apt-get install cmake make g++ libfftw3-dev dpkg-dev time
#      (not `apt-get build-dep gromacs`: that pulls MPI, CUDA/OpenCL headers, Sphinx,
#      LaTeX and hwloc, none of which this single-rank CPU build uses)
#   3. cd $GMX_PREFIX/src && apt-get source gromacs        (-> gromacs-2022.5/)
#   4. for each of GMX_PRECISIONS (mixed, then double), in $GMX_PREFIX/build-PREC:
#        cmake -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=$GMX_PREFIX/install
#              -DGMX_SIMD=<AVX_512 if the CPU has avx512f, else AVX2_256 with avx2,
#                          else SSE4.1 with sse4_1, else None; GMX_SIMD overrides>
#              -DGMX_DOUBLE=OFF|ON -DGMX_GPU=OFF -DGMX_MPI=OFF -DGMX_OPENMP=ON
#              -DGMX_BUILD_OWN_FFTW=OFF -DGMX_FFT_LIBRARY=fftw3 (Debian's fftw3)
#              -DBUILD_TESTING=OFF -DREGRESSIONTEST_DOWNLOAD=OFF -DGMX_HWLOC=OFF
#              -DGMX_X11=OFF -DGMXAPI=OFF -DGMX_INSTALL_NBLIB_API=OFF
#              -DGMX_BUILD_HELP=OFF -DGMX_BUILD_MANUAL=OFF
#        nice -n 19 make -j$GMX_JOBS && nice -n 19 make install
#      giving $GMX_PREFIX/install/bin/gmx (mixed precision) and gmx_d (double), g++ 12.2
#      with GROMACS's Release flags (-O3 -funroll-all-loops and its SIMD -m flags; for
#      AVX_512: -mavx512f -mfma -mavx512vl -mavx512dq -mavx512bw). On 2 cores shared
#      with other work (load 2-4) the mixed build took 21 minutes, the double one 20;
#      each precision's wall time is written to $GMX_PREFIX/build-PREC.seconds and its
#      log to $GMX_PREFIX/build-PREC.log.
#
# The system (lj_start_gromacs.py, gromacs_lj3d_inlj.mdp): in.lj in GROMACS units with an
# argon-like sigma = 0.34 nm, epsilon = 0.996 kJ/mol, m = 39.948 u, so
# tau = sigma sqrt(m / epsilon) = 2.15326 ps and dt = 0.005 tau = 0.0107663 ps; fcc,
# 20^3 cells = 32,000 atoms at rho* 0.8442, velocities at T* = 1.44; LJ cut at 2.5 sigma
# (vdw-modifier = None: not shifted, like lj/cut; DispCorr = no), zero charges
# (coulombtype = Cut-off; GROMACS's kernels then take their LJ-only path, and md.log's
# flop table shows "NxN LJ" lines only), NVE (leap-frog `md`, no coupling, no
# constraints), no trajectory output, energies every 100 steps.
#   variant "mixed":    gmx,   in.lj's list: rlist = 2.8 sigma, nstlist = 20,
#                       verlet-buffer-tolerance = -1 (no automatic buffer, no pruning)
#   variant "double":   gmx_d, the same settings
#   variant "defaults": gmx,   GROMACS's own list defaults (gromacs_lj3d_defaults.mdp:
#                       no rlist, nstlist or verlet-buffer-tolerance). In NVE, mdrun
#                       neither raises nstlist nor prunes dynamically ("Can not increase
#                       nstlist because an NVE ensemble is used"): nstlist 10, and the
#                       default tolerance 0.005 kJ/mol/ps at the start's 172.5 K gives
#                       rlist = rc (the 4x8 cluster list's own margin suffices)
#   variant "defaults-nvt": gmx, the same with a v-rescale thermostat
#                       (gromacs_lj3d_defaults_nvt.mdp: T* 0.71, in.lj's temperature
#                       after the melt; tau-t = 0.1 tau), with which mdrun raises nstlist
#                       and prunes the list dynamically: what a GROMACS user runs
# pedesis: pedesis_lj3d.toml (skin 0.3: list range 2.8, rebuilt when a pair within the
# cutoff could be missing; formats = []), the same start as JSON.
#
# The same start: with LAMMPS installed (`lmp`, Debian's `apt-get install lammps`)
# LAMMPS makes it exactly as lammps_side_by_side.sh's lj3d (lammps_lj3d.in -var mode
# gen: lattice fcc 0.8442, velocity create 1.44 87287 loop geom), converted to pedesis's
# JSON by lammps_data_to_json.py; without it (or START=python) lj_start_gromacs.py fcc
# builds the lattice and Gaussian velocities itself. Either way lj_start_gromacs.py gro
# writes the .gro (12 decimals per field, GROMACS's variable-precision reading) and
# .top from that JSON, so both codes start from the same positions and velocities.
# GROMACS's leap-frog takes the start's velocities as v(-dt/2), pedesis's velocity
# Verlet as v(0): the trajectories differ from step 1 by O(dt) and, the fluid being
# chaotic, decorrelate within a few hundred steps; thermodynamics agree. GROMACS reports
# the kinetic energy as the average of the two half-step values (O(dt^2) from the
# full-step one).
#
# Modes:
#   build   build GROMACS as above (long: run it under nohup; see the example below)
#   check   CHECK_STEPS steps of each variant whose binary exists and of pedesis from
#           the same start; T* = kB T / epsilon and P* = P sigma^3 / epsilon from
#           GROMACS's energy file (kB = 0.00831446261815324 kJ/mol/K, 16.6053906660 bar
#           per kJ mol^-1 nm^-3, GROMACS's own constants) beside pedesis's log.csv
#           (temperature, pressure, potential_energy) at a few steps and averaged over
#           the second half; it states whether T agrees to 1 % and P to 3 % (exit 1 if
#           not). Variant defaults-nvt is left out: thermostatted from step 0 it takes
#           another path from the fcc start
#   pairs   for each of VARIANTS: PAIRS alternations (GROMACS, then pedesis) of STEPS
#           steps; whole-process CPU time (user + sys, GNU time -v) of `gmx mdrun` and
#           of `pedesis run`, each code's own timed window (GROMACS's md.log "Time:"
#           wall seconds, which cover its MD loop; pedesis's summary.json wall_seconds,
#           its steps after set-up), GROMACS's cycle accounting lines "Neighbor search"
#           and "Force" (wall seconds, from md.log), and the median and range of the
#           per-pair ratios pedesis speed / GROMACS speed (= GROMACS CPU / pedesis CPU,
#           and the same for the windows). grompp runs once per variant, untimed;
#           mdrun runs as `gmx -quiet mdrun -ntmpi 1 -ntomp 1 -nb cpu -pin off
#           -noconfout` (GROMACS writes its final checkpoint, as pedesis does).
#   Both codes run with OMP_NUM_THREADS=1.
#
# Usage:
#   docs/bench/gromacs_side_by_side.sh build|check|pairs
# Environment (defaults in brackets):
#   GMX_PREFIX     where GROMACS's source, builds and install live  [/work/peers/gromacs]
#   GMX_PRECISIONS build: which to build, in order                  ["mixed double"]
#   GMX_SIMD       build: GROMACS's GMX_SIMD                        [from /proc/cpuinfo]
#   GMX_JOBS       build: make -j                                   [2]
#   GMX_SKIP_APT   build: 1 = no apt-get steps (source already in $GMX_PREFIX/src)
#   GMX, GMX_D     mixed and double binaries   [$GMX_PREFIX/install/bin/gmx, gmx_d]
#   VARIANTS       subset of "mixed double defaults defaults-nvt"   [all four]
#   PAIRS          alternations per variant                          [6]
#   STEPS          steps of each timed run                           [2000]
#   CHECK_STEPS    check: steps                                      [1000]
#   CHECK_EVERY    check: steps between the rows compared            [10]
#   START          lammps or python (the start's maker; see above)   [lammps if lmp runs]
#   LMP            LAMMPS binary for START=lammps                    [lmp]
#   PEDESIS        pedesis binary                                    [<repo>/build/pedesis]
#   PEDESIS_PRECISION  pairs: pedesis's --precision, double or mixed  [double]
#   SCRATCH        scratch directory outside the repository          [mktemp -d]
#   KEEP_SCRATCH   1 = keep it (start, inputs, logs, md.log files)
#   RESULTS        optional path: copy the per-run TSV (pairs) there
# Examples:
#   nohup docs/bench/gromacs_side_by_side.sh build > /work/peers/gromacs-build.log 2>&1 &
#   docs/bench/gromacs_side_by_side.sh check
#   PAIRS=1 STEPS=100 docs/bench/gromacs_side_by_side.sh pairs      (smoke test)
# Time only on a quiet machine; compare the per-pair ratios, not absolute times.

set -euo pipefail

prog=gromacs_side_by_side

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_root=$(cd "$script_dir/../.." && pwd -P)
# shellcheck source=bench_common.sh
source "$script_dir/bench_common.sh"

MODE=${1:-}
PEDESIS_PRECISION=${PEDESIS_PRECISION:-double}
[[ $PEDESIS_PRECISION == double || $PEDESIS_PRECISION == mixed ]] ||
    die "PEDESIS_PRECISION must be double or mixed, not '$PEDESIS_PRECISION'"
GMX_PREFIX=${GMX_PREFIX:-/work/peers/gromacs}
GMX_PRECISIONS=${GMX_PRECISIONS:-"mixed double"}
GMX_SIMD=${GMX_SIMD:-}
GMX_JOBS=${GMX_JOBS:-2}
GMX_SKIP_APT=${GMX_SKIP_APT:-0}
GMX=${GMX:-$GMX_PREFIX/install/bin/gmx}
GMX_D=${GMX_D:-$GMX_PREFIX/install/bin/gmx_d}
VARIANTS=${VARIANTS:-"mixed double defaults defaults-nvt"}
PAIRS=${PAIRS:-6}
STEPS=${STEPS:-2000}
CHECK_STEPS=${CHECK_STEPS:-1000}
CHECK_EVERY=${CHECK_EVERY:-10}
START=${START:-}
LMP=${LMP:-lmp}
PEDESIS=${PEDESIS:-$repo_root/build/pedesis}
SCRATCH=${SCRATCH:-}
KEEP_SCRATCH=${KEEP_SCRATCH:-0}
RESULTS=${RESULTS:-}
PYTHON=/usr/bin/python3

# in.lj in GROMACS units (the .mdp files carry dt and the cut-offs for these values)
SIGMA=0.34
EPSILON=0.996
MASS=39.948
KB=0.00831446261815324     # GROMACS's c_boltz, kJ/(mol K)
PRESFAC=16.6053906660      # GROMACS's c_presfac, bar per kJ mol^-1 nm^-3
NATOMS=32000

usage() {
    echo "usage: $0 build|check|pairs   (the header of this script explains each mode)" >&2
    exit 2
}

# ---------------------------------------------------------------- build
cpu_simd() {
    local flags
    flags=$(awk -F': *' '/^flags/ { print " " $2 " "; exit }' /proc/cpuinfo)
    case $flags in
        *" avx512f "*) echo AVX_512 ;;
        *" avx2 "*) echo AVX2_256 ;;
        *" sse4_1 "*) echo SSE4.1 ;;
        *) echo None ;;
    esac
}

do_build() {
    local simd=${GMX_SIMD:-$(cpu_simd)} src prec bdir t0 dbl
    for prec in $GMX_PRECISIONS; do
        [[ $prec == mixed || $prec == double ]] || die "GMX_PRECISIONS: mixed and/or double (got '$prec')"
    done
    mkdir -p "$GMX_PREFIX/src"
    case "$(cd "$GMX_PREFIX" && pwd -P)/" in
        "$repo_root"/*) die "GMX_PREFIX must lie outside the repository ($repo_root)" ;;
    esac
    if [[ $GMX_SKIP_APT != 1 ]]; then
        [[ $(id -u) == 0 ]] || die "build runs apt-get: run it as root, or do the apt steps of the header by hand and set GMX_SKIP_APT=1"
        local list=/etc/apt/sources.list.d/pedesis-deb-src.sources
        if [[ ! -f $list ]]; then
            printf '%s\n' "Types: deb-src" "URIs: http://deb.debian.org/debian" "Suites: bookworm" \
                "Components: main" "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg" >"$list"
            note "wrote $list"
        fi
        apt-get update
        DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
            cmake make g++ libfftw3-dev dpkg-dev time
        if ! compgen -G "$GMX_PREFIX/src/gromacs-*/CMakeLists.txt" >/dev/null; then
            (cd "$GMX_PREFIX/src" && apt-get source gromacs)
        fi
    fi
    src=$(compgen -G "$GMX_PREFIX/src/gromacs-*/CMakeLists.txt" | head -1 || true)
    [[ -n $src ]] || die "no GROMACS source under $GMX_PREFIX/src (apt-get source gromacs there)"
    src=$(dirname "$src")
    note "source $src, GMX_SIMD=$simd, install into $GMX_PREFIX/install"
    for prec in $GMX_PRECISIONS; do
        bdir="$GMX_PREFIX/build-$prec"
        dbl=OFF
        [[ $prec == double ]] && dbl=ON
        note "building $prec precision in $bdir (log $GMX_PREFIX/build-$prec.log)"
        t0=$SECONDS
        {
            cmake -S "$src" -B "$bdir" -DCMAKE_BUILD_TYPE=Release \
                -DCMAKE_INSTALL_PREFIX="$GMX_PREFIX/install" -DGMX_SIMD="$simd" \
                -DGMX_DOUBLE=$dbl -DGMX_GPU=OFF -DGMX_MPI=OFF -DGMX_OPENMP=ON \
                -DGMX_BUILD_OWN_FFTW=OFF -DGMX_FFT_LIBRARY=fftw3 -DBUILD_TESTING=OFF \
                -DREGRESSIONTEST_DOWNLOAD=OFF -DGMX_HWLOC=OFF -DGMX_X11=OFF -DGMXAPI=OFF \
                -DGMX_INSTALL_NBLIB_API=OFF -DGMX_BUILD_HELP=OFF -DGMX_BUILD_MANUAL=OFF &&
                nice -n 19 make -C "$bdir" -j"$GMX_JOBS" &&
                nice -n 19 make -C "$bdir" install
        } >"$GMX_PREFIX/build-$prec.log" 2>&1 ||
            { tail -n 30 "$GMX_PREFIX/build-$prec.log" >&2; die "$prec build failed (log $GMX_PREFIX/build-$prec.log)"; }
        echo $((SECONDS - t0)) >"$GMX_PREFIX/build-$prec.seconds"
        note "$prec precision built in $((SECONDS - t0)) s"
    done
    for b in gmx gmx_d; do
        [[ -x $GMX_PREFIX/install/bin/$b ]] && note "$GMX_PREFIX/install/bin/$b: $(gmx_desc "$GMX_PREFIX/install/bin/$b")"
    done
    return 0
}

# "GROMACS version 2022.5, mixed precision, SIMD AVX_512" from `gmx --version`
gmx_desc() {
    "$1" -quiet --version 2>/dev/null | awk -F': *' '
        /^GROMACS version/ { v = $2 } /^Precision/ { p = $2 } /^SIMD instructions/ { s = $2 }
        /^C\+\+ compiler:/ { c = $2 }
        END { printf "GROMACS %s, %s precision, SIMD %s, %s\n", v, p, s, c }'
}

case $MODE in
    build)
        do_build
        exit 0
        ;;
    check | pairs) ;;
    *) usage ;;
esac

# ---------------------------------------------------------------- checks
is_uint "$PAIRS" && ((10#$PAIRS >= 1)) || die "PAIRS must be a positive integer (got '$PAIRS')"
is_uint "$STEPS" && ((10#$STEPS >= 1)) || die "STEPS must be a positive integer (got '$STEPS')"
is_uint "$CHECK_STEPS" && ((10#$CHECK_STEPS >= 2)) || die "CHECK_STEPS must be an integer >= 2 (got '$CHECK_STEPS')"
is_uint "$CHECK_EVERY" && ((10#$CHECK_EVERY >= 1)) || die "CHECK_EVERY must be a positive integer (got '$CHECK_EVERY')"
PAIRS=$((10#$PAIRS))
STEPS=$((10#$STEPS))
CHECK_STEPS=$((10#$CHECK_STEPS))
CHECK_EVERY=$((10#$CHECK_EVERY))
((CHECK_STEPS % CHECK_EVERY == 0)) || die "CHECK_STEPS ($CHECK_STEPS) must be a multiple of CHECK_EVERY ($CHECK_EVERY)"
read -r -a variants <<<"$VARIANTS"
((${#variants[@]} >= 1)) || die "VARIANTS is empty"
for v in "${variants[@]}"; do
    case $v in mixed | double | defaults | defaults-nvt) ;; *) die "unknown variant '$v' (mixed, double, defaults, defaults-nvt)" ;; esac
done
[[ -x /usr/bin/time ]] || die "/usr/bin/time (GNU time, for CPU time) not found; apt-get install time"
[[ -x $PYTHON ]] || die "$PYTHON not found (the start's converter needs it)"
[[ -x $PEDESIS ]] || die "pedesis binary not found or not executable: $PEDESIS (build it first, or set PEDESIS)"
for f in lj_start_gromacs.py lammps_data_to_json.py lammps_lj3d.in pedesis_lj3d.toml \
    gromacs_lj3d_inlj.mdp gromacs_lj3d_defaults.mdp gromacs_lj3d_defaults_nvt.mdp; do
    [[ -f $script_dir/$f ]] || die "missing $script_dir/$f"
done
if [[ -z $START ]]; then
    START=python
    lmp_help=$("$LMP" -h 2>/dev/null || true)
    [[ $lmp_help == *"Large-scale Atomic/Molecular"* ]] && START=lammps
fi
[[ $START == lammps || $START == python ]] || die "START must be lammps or python (got '$START')"

var_bin() { # variant -> binary
    case $1 in double) echo "$GMX_D" ;; *) echo "$GMX" ;; esac
}
var_mdp() { # variant -> .mdp template
    case $1 in
        defaults) echo "$script_dir/gromacs_lj3d_defaults.mdp" ;;
        defaults-nvt) echo "$script_dir/gromacs_lj3d_defaults_nvt.mdp" ;;
        *) echo "$script_dir/gromacs_lj3d_inlj.mdp" ;;
    esac
}
# check runs what is built (the double build may come later); pairs needs every variant
usable=()
for v in "${variants[@]}"; do
    b=$(var_bin "$v")
    if [[ -x $b ]]; then
        usable+=("$v")
    elif [[ $MODE == pairs ]]; then
        die "variant $v needs $b (run '$0 build', or set GMX / GMX_D, or leave $v out of VARIANTS)"
    else
        note "variant $v skipped: no $b (run '$0 build')"
    fi
done
((${#usable[@]} >= 1)) || die "no GROMACS binary found (run '$0 build')"

scratch_entries=(start check pairs results.tsv)
make_scratch gromacs_side

# ---------------------------------------------------------------- helpers
cpu_s() { # GNU time -v file -> user + sys seconds
    local user sys
    user=$(time_field "User time \\(seconds\\)" "$1")
    sys=$(time_field "System time \\(seconds\\)" "$1")
    [[ -n $user && -n $sys ]] || die "could not read /usr/bin/time output $1"
    awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f\n", u + s }'
}
timed() { # label log timefile cmd...   (in the current directory)
    local label=$1 log=$2 tf=$3
    shift 3
    if ! OMP_NUM_THREADS=1 GMX_MAXBACKUP=-1 /usr/bin/time -v -o "$tf" "$@" >"$log" 2>&1; then
        tail -n 20 "$log" >&2
        die "$label failed (log above; full log in $log, kept with KEEP_SCRATCH=1)"
    fi
}
set_key() { # file key value: replace the one line "key = ..." (checked; any spacing)
    local n
    n=$(grep -cE "^$2 +=" "$1" || true)
    [[ $n == 1 ]] || die "$1: expected one '$2 =' line, found $n"
    sed -i -E "s|^($2 +=).*|\\1 $3|" "$1"
}
jkey() { # key summary.json -> value
    awk -v k="\"$1\":" '$1 == k { v = $2; sub(/,$/, "", v); print v; exit }' "$2"
}

# the common start in $SCRATCH/start: start.json (reduced units), start.gro, start.top
make_start() {
    local d="$SCRATCH/start"
    rm -rf -- "$d"
    mkdir -p "$d"
    if [[ $START == lammps ]]; then
        (cd "$d" && "$LMP" -nocite -log none -in "$script_dir/lammps_lj3d.in" -var mode gen \
            -var data start.data >gen.log 2>&1) || { tail -n 20 "$d/gen.log" >&2; die "LAMMPS could not write the start"; }
        "$PYTHON" "$script_dir/lammps_data_to_json.py" --dim 3 --style atomic --radius 0.5 \
            "$d/start.data" "$d/start.json" 2>"$d/convert.log" || { cat "$d/convert.log" >&2; die "conversion of the LAMMPS data file failed"; }
    else
        "$PYTHON" "$script_dir/lj_start_gromacs.py" fcc --cells 20 --rho 0.8442 --temp 1.44 \
            --seed 87287 "$d/start.json" 2>"$d/convert.log" || { cat "$d/convert.log" >&2; die "lj_start_gromacs.py fcc failed"; }
    fi
    "$PYTHON" "$script_dir/lj_start_gromacs.py" gro --sigma $SIGMA --epsilon $EPSILON --mass $MASS \
        "$d/start.json" "$d/start.gro" "$d/start.top" 2>>"$d/convert.log" || { cat "$d/convert.log" >&2; die "lj_start_gromacs.py gro failed"; }
    local n
    n=$(sed -n 2p "$d/start.gro" | tr -d ' ')
    [[ $n == "$NATOMS" ]] || die "the start has $n atoms, expected $NATOMS"
}

# gmx_tpr variant dir steps nstcalcenergy: dir/run.tpr from the variant's .mdp
gmx_tpr() {
    local v=$1 d=$2 bin
    bin=$(var_bin "$v")
    mkdir -p "$d"
    cp -- "$(var_mdp "$v")" "$d/run.mdp"
    set_key "$d/run.mdp" nsteps "$3"
    set_key "$d/run.mdp" nstcalcenergy "$4"
    set_key "$d/run.mdp" nstenergy "$4"
    (cd "$d" && GMX_MAXBACKUP=-1 "$bin" -quiet grompp -f run.mdp -c "$SCRATCH/start/start.gro" \
        -p "$SCRATCH/start/start.top" -o run.tpr -po mdout.mdp -maxwarn 0 >grompp.log 2>&1) ||
        { tail -n 30 "$d/grompp.log" >&2; die "$v: grompp failed (log $d/grompp.log)"; }
}
# pedesis_toml dir steps log_every: dir/run.toml from pedesis_lj3d.toml
pedesis_toml() {
    mkdir -p "$1"
    cp -- "$script_dir/pedesis_lj3d.toml" "$1/run.toml"
    set_key "$1/run.toml" file "\"$SCRATCH/start/start.json\""
    set_key "$1/run.toml" steps "$2"
    set_key "$1/run.toml" log_every "$3"
}
# md.log's lines on the kernels and the pair list (setup, nstlist changes, pruning)
list_lines() {
    awk '/^Using .*kernels|^Changing nstlist|^Can not increase nstlist|nstlist.*command line/ { print; next }
         /^Using .*pair-list setup/ { show = 1 } show && /^$/ { show = 0 } show { print }' "$1"
}
mdrun_cmd() { # variant -> the mdrun command line (run in the run's directory)
    echo "$(var_bin "$1") -quiet mdrun -s run.tpr -deffnm gmx -ntmpi 1 -ntomp 1 -nb cpu -pin off -noconfout"
}

describe_pedesis "$PEDESIS"
echo "== GROMACS vs pedesis run, in.lj (32,000 LJ atoms, rho* 0.8442, rc 2.5 sigma, NVE, dt 0.005 tau), one thread each"
echo "cpu:       ${cpu:-unknown}  ($(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg))"
for v in "${usable[@]}"; do
    printf '%-10s %s: %s\n' "$v:" "$(var_bin "$v")" "$(gmx_desc "$(var_bin "$v")")"
done
echo "pedesis:   $PEDESIS @ $ped_rev$ped_dirty${ped_flags:+, $ped_flags}, --precision $PEDESIS_PRECISION"
echo "start:     made by $START (sigma $SIGMA nm, epsilon $EPSILON kJ/mol, m $MASS u)"
make_start

# ---------------------------------------------------------------- check
if [[ $MODE == check ]]; then
    cdir="$SCRATCH/check"
    rm -rf -- "$cdir"
    echo "check:     $CHECK_STEPS steps, rows every $CHECK_EVERY steps compared"
    echo
    xvgs=()
    for v in "${usable[@]}"; do
        if [[ $v == defaults-nvt ]]; then
            # thermostatted from step 0 it takes another path from the fcc start than NVE
            # (T* 0.71 at once instead of through the melt): not comparable step by step
            echo "defaults-nvt: not checked (a thermostat, not NVE; otherwise the physics of 'defaults')"
            continue
        fi
        gmx_tpr "$v" "$cdir/$v" "$CHECK_STEPS" "$CHECK_EVERY"
        # shellcheck disable=SC2046
        (cd "$cdir/$v" && timed "$v: mdrun" mdrun.log mdrun.time $(mdrun_cmd "$v"))
        (cd "$cdir/$v" && printf 'Potential\nTemperature\nPressure\n\n' |
            "$(var_bin "$v")" -quiet energy -f gmx.edr -o energy.xvg >energy.log 2>&1) ||
            { tail -n 20 "$cdir/$v/energy.log" >&2; die "$v: gmx energy failed"; }
        list_lines "$cdir/$v/gmx.log" | sed "s/^/$v: /"
        if grep -q 'NxN LJ' "$cdir/$v/gmx.log" && ! grep -q 'Elec\.' "$cdir/$v/gmx.log"; then
            echo "$v: md.log's flop count has LJ-only kernels (no Coulomb)"
        else
            echo "$v: md.log's flop count shows Coulomb kernels (see $cdir/$v/gmx.log)"
        fi
        xvgs+=("$v=$cdir/$v/energy.xvg")
    done
    pedesis_toml "$cdir/pedesis" "$CHECK_STEPS" "$CHECK_EVERY"
    (cd "$cdir/pedesis" && timed "pedesis run" run.log run.time "$PEDESIS" run run.toml --out out)
    echo
    "$PYTHON" - "$cdir/pedesis/out/log.csv" "$NATOMS" "$CHECK_STEPS" "$CHECK_EVERY" \
        "$SIGMA" "$EPSILON" "$MASS" "$KB" "$PRESFAC" "${xvgs[@]}" <<'PY'
import csv, sys

log, n, steps, every = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
sigma, eps, mass, kb, presfac = (float(x) for x in sys.argv[5:10])
dt = 0.005 * sigma * (mass / eps) ** 0.5

rows = {}
with open(log) as f:
    for r in csv.DictReader(f):
        s = int(r["step"])
        rows[s] = {"T": float(r["temperature"]), "P": float(r["pressure"]),
                   "U": float(r["potential_energy"]) / n}
codes = [("pedesis", rows)]
for arg in sys.argv[10:]:
    name, path = arg.split("=", 1)
    legend, data = {}, {}
    for line in open(path):
        if line.startswith("@") and " legend " in line and line.split()[1].startswith("s"):
            legend[int(line.split()[1][1:])] = line.split('"')[1]
        elif line[0] not in "#@":
            t = [float(x) for x in line.split()]
            s = int(round(t[0] / dt))
            vals = dict(zip((legend[i] for i in range(len(t) - 1)), t[1:]))
            data[s] = {"T": kb * vals["Temperature"] / eps,
                       "P": vals["Pressure"] / presfac * sigma ** 3 / eps,
                       "U": vals["Potential"] / (n * eps)}
    codes.append(("gmx-" + name, data))

show = [s for s in (0, every, 10 * every, steps // 2, steps) if s <= steps]
show = sorted(set(show))
w = 2 + max(len(c) + 6 for c, _ in codes)
print("reduced units: T* = kB T / epsilon, P* = P sigma^3 / epsilon, U* = potential / (N epsilon)")
print("%-6s" % "step" + "".join("%*s" % (w, c + " " + q) for q in ("T*", "P*", "U*/N")
                                for c, _ in codes))
for s in show:
    cells = []
    for q in ("T", "P", "U"):
        for _, d in codes:
            cells.append("%*.5f" % (w, d[s][q]) if s in d else "%*s" % (w, "-"))
    print("%-6d" % s + "".join(cells))
half = [s for s in range(steps // 2, steps + 1, every)]
means = {}
for c, d in codes:
    missing = [s for s in half if s not in d]
    if missing:
        sys.exit("%s: no row at step %d" % (c, missing[0]))
    means[c] = {q: sum(d[s][q] for s in half) / len(half) for q in ("T", "P", "U")}
print("%-6s" % "mean" + "".join("%*.5f" % (w, means[c][q]) for q in ("T", "P", "U")
                                for c, _ in codes)
      + "   (steps %d..%d, %d rows)" % (half[0], half[-1], len(half)))
ok = True
for c, _ in codes[1:]:
    dT = 100 * (means[c]["T"] / means["pedesis"]["T"] - 1)
    dP = 100 * (means[c]["P"] / means["pedesis"]["P"] - 1)
    dU = 100 * (means[c]["U"] / means["pedesis"]["U"] - 1)
    good = abs(dT) < 1 and abs(dP) < 3
    ok = ok and good
    print("%s vs pedesis, means: T* %+.2f %%, P* %+.2f %%, U*/N %+.2f %% -> %s" %
          (c, dT, dP, dU, "agree (T within 1 %, P within 3 %)" if good else "DIFFER"))
sys.exit(0 if ok else 1)
PY
    exit
fi

# ---------------------------------------------------------------- pairs
pdir="$SCRATCH/pairs"
rm -rf -- "$pdir"
echo "runs:      variants: ${variants[*]}; $PAIRS pair(s) each (GROMACS, then pedesis); $STEPS steps each"
echo "           cpu: user + sys of the whole process (GNU time -v); window: GROMACS md.log \"Time:\""
echo "           wall seconds, pedesis summary.json wall_seconds; ratio: pedesis speed / GROMACS speed"
echo
tsv="$SCRATCH/results.tsv"
printf 'variant\tpair\tcode\tcpu_s\twindow_s\tsearch_s\tforce_s\tlist_builds\n' >"$tsv"
col() { # variant code column-number -> values
    awk -F'\t' -v v="$1" -v c="$2" -v k="$3" 'NR > 1 && $1 == v && $3 == c && $k != "" { print $k }' "$tsv"
}
summary_lines=()
pedesis_toml "$pdir/pedesis" "$STEPS" "$STEPS"
nstcalc=$((STEPS < 100 ? STEPS : 100))
for v in "${variants[@]}"; do
    gmx_tpr "$v" "$pdir/$v" "$STEPS" "$nstcalc"
    echo "== $v: $(mdrun_cmd "$v")   ($(basename "$(var_mdp "$v")"))"
    printf '%-4s %9s %9s %7s %10s %10s %7s %9s %9s\n' pair "gmx cpu" "ped cpu" ratio \
        "gmx window" "ped window" ratio "gmx srch" "gmx force"
    for ((i = 1; i <= PAIRS; i++)); do
        g="$pdir/$v/run.$i"
        mkdir -p "$g"
        ln -sf ../run.tpr "$g/run.tpr"
        # shellcheck disable=SC2046
        (cd "$g" && timed "$v: mdrun (pair $i)" mdrun.log mdrun.time $(mdrun_cmd "$v"))
        gcpu=$(cpu_s "$g/mdrun.time")
        gwin=$(awk '$1 == "Time:" { print $3 }' "$g/gmx.log")
        gsearch=$(awk '/^ Neighbor search / { print $6; exit }' "$g/gmx.log")
        gforce=$(awk '/^ Force / { print $5; exit }' "$g/gmx.log")
        gbuilds=$(awk '/^ Neighbor search / { print $5; exit }' "$g/gmx.log")
        is_num "$gwin" || die "$v: no \"Time:\" line in $g/gmx.log"
        printf '%s\t%s\tgromacs\t%s\t%s\t%s\t%s\t%s\n' "$v" "$i" "$gcpu" "$gwin" "$gsearch" "$gforce" "$gbuilds" >>"$tsv"

        p="$pdir/pedesis/run.$v.$i"
        rm -rf -- "$p"
        (cd "$pdir/pedesis" && timed "pedesis (pair $i)" "run.$v.$i.log" "run.$v.$i.time" \
            "$PEDESIS" run run.toml --out "run.$v.$i" --precision "$PEDESIS_PRECISION")
        sj="$p/summary.json"
        [[ -f $sj ]] || die "pedesis wrote no summary.json ($pdir/pedesis/run.$v.$i.log)"
        [[ $(jkey steps "$sj") == "$STEPS" && $(jkey particles "$sj") == "$NATOMS" ]] ||
            die "pedesis summary $sj is not for $STEPS steps of $NATOMS particles"
        pcpu=$(cpu_s "$pdir/pedesis/run.$v.$i.time")
        pwin=$(jkey wall_seconds "$sj")
        printf '%s\t%s\tpedesis\t%s\t%s\t\t\t%s\n' "$v" "$i" "$pcpu" "$pwin" "$(jkey list_rebuilds "$sj")" >>"$tsv"
        awk -v i="$i" -v gc="$gcpu" -v pc="$pcpu" -v gw="$gwin" -v pw="$pwin" -v gs="$gsearch" -v gf="$gforce" 'BEGIN {
            printf "%-4s %9.2f %9.2f %7.3f %10.3f %10.3f %7.3f %9s %9s\n", i, gc, pc, gc / pc, gw, pw, gw / pw, gs, gf }'
    done
    list_lines "$pdir/$v/run.1/gmx.log"
    ratios() { # column -> per-pair ratios gromacs / pedesis
        awk -F'\t' -v v="$v" -v k="$1" 'NR > 1 && $1 == v { if ($3 == "gromacs") g[$2] = $k; else p[$2] = $k }
            END { for (i in g) print g[i] / p[i] }' "$tsv"
    }
    rc=$(ratios 4)
    rw=$(ratios 5)
    med() { median <<<"$1"; }
    lo() { sort -g <<<"$1" | head -1; }
    hi() { sort -g <<<"$1" | tail -1; }
    printf 'pedesis speed / GROMACS speed, median of %d pair(s) (range): whole-process cpu %.3f (%.3f - %.3f); own windows %.3f (%.3f - %.3f)\n' \
        "$PAIRS" "$(med "$rc")" "$(lo "$rc")" "$(hi "$rc")" "$(med "$rw")" "$(lo "$rw")" "$(hi "$rw")"
    m() { col "$v" "$1" "$2" | median; }
    printf 'medians: GROMACS cpu %.2f s, window %.3f s (neighbor search %s s in %s calls, force %s s); pedesis cpu %.2f s, window %.3f s, %s list builds\n' \
        "$(m gromacs 4)" "$(m gromacs 5)" "$(m gromacs 6)" "$(m gromacs 8)" "$(m gromacs 7)" \
        "$(m pedesis 4)" "$(m pedesis 5)" "$(m pedesis 8)"
    echo
    summary_lines+=("$(printf '%-12s %10.3f %7.3f-%-7.3f %10.3f %9.2f %9.2f %9s %9s' "$v" \
        "$(med "$rc")" "$(lo "$rc")" "$(hi "$rc")" "$(med "$rw")" "$(m gromacs 4)" "$(m pedesis 4)" \
        "$(m gromacs 6)" "$(m gromacs 7)")")
done

echo "== summary: pedesis speed / GROMACS speed, $STEPS steps, $PAIRS pair(s), one thread"
printf '%-12s %10s %15s %10s %9s %9s %9s %9s\n' variant "cpu ratio" range "win ratio" "gmx cpu" "ped cpu" \
    "gmx srch" "gmx force"
for line in "${summary_lines[@]}"; do echo "$line"; done
echo "(medians over the pairs; cpu: whole process, s; srch, force: GROMACS's cycle accounting, wall s)"
if [[ -n $RESULTS ]]; then
    cp -- "$tsv" "$RESULTS"
    note "per-run results written to $RESULTS"
fi
