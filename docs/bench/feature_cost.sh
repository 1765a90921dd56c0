#!/bin/sh
# The cost of each issue-50 term relative to a periodic ABP run: 2D WCA ABPs (N = 20000,
# area fraction 0.4), 2000 steps, one thread, the base run and the run with one more term
# alternated (A B A B ...) PAIRS times; prints the median and range of the per-pair ratios
# of stepping seconds (summary.json's stepping_seconds; > 1: the term costs that much).
# Usage: docs/bench/feature_cost.sh [PEDESIS] [PAIRS]
set -eu
bin=${1:-build/pedesis}
pairs=${2:-6}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
base() { # $1: boundary
    cat <<TOML
dimension = 2
dynamics = "brownian"
seed = 2
[initial]
min_distance = 1.0
[box]
lengths = [200.0, 100.0]
boundary = $1
[[species]]
name = "A"
count = 10000
radius = 0.5
[[force]]
name = "wca"
epsilon = 1.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0
[run]
steps = 2000
dt = 0.002
[output]
log_every = 2000
formats = []
TOML
}
rotation='[[integrator]]
name = "brownian_rotation"
T = 0.5
gamma = 1.0'
base '"periodic"' > "$dir/periodic.toml"; echo "$rotation" >> "$dir/periodic.toml"
variant() { # $1: name, $2: boundary, $3: extra tables
    base "$2" > "$dir/$1.toml"
    printf '%s\n' "$3" >> "$dir/$1.toml"
}
variant walls '["wall", "periodic"]' "$rotation
[[force]]
name = \"wall\"
potential = \"harmonic\"
k = 50.0"
variant container '"periodic"' "$rotation
[[force]]
name = \"wall\"
shape = \"sphere\"
potential = \"harmonic\"
k = 10.0
radius = 120.0"
variant gravity '"periodic"' "$rotation
[[force]]
name = \"gravity\"
force = 0.1"
variant trap '"periodic"' "$rotation
[[force]]
name = \"harmonic_trap\"
k = 0.001"
variant chiral '"periodic"' "$rotation
[[torque]]
name = \"active_torque\"
torque = 0.5"
variant tumble '"periodic"' "[[integrator]]
name = \"run_and_tumble\"
rate = 0.5"
variant nematic '"periodic"' "$rotation
[[torque]]
name = \"nematic_align\"
J = 1.0
a = 2.0"
variant aoup '"periodic"' "$rotation
[[force]]
name = \"active_ou\"
tau = 1.0
D_a = 0.5"
seconds() {
    OMP_NUM_THREADS=1 "$bin" run "$dir/$1.toml" --out "$dir/out_$1" --threads 1 >/dev/null
    sed -n 's/.*"stepping_seconds": *\([0-9.e+-]*\).*/\1/p' "$dir/out_$1/summary.json"
}
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
for v in walls container gravity trap chiral tumble nematic aoup; do
    ratios=""
    k=0
    while [ $k -lt "$pairs" ]; do
        a=$(seconds periodic)
        b=$(seconds "$v")
        ratios="$ratios $(echo "$b / $a" | bc -l)"
        k=$((k + 1))
    done
    echo "$ratios" | tr ' ' '\n' | sed '/^$/d' | sort -g | awk -v v="$v" '
        { r[NR] = $1 }
        END { m = (NR % 2) ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2
              printf "%-10s cost %.3f x periodic ABPs (range %.3f-%.3f, %d pairs)\n", v, m, r[1], r[NR], NR }'
done
