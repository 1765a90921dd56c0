#!/bin/sh
# The cost of [transport] and of the image counts (issue 51), one thread, whole-process
# CPU time (user + sys), each pair alternated (A B A B ...) PAIRS times; prints the median
# and range of the per-pair ratios (> 1: the second costs that much more).
#  1. event engine, 1372 hard spheres at n = 0.5, t = 300: BASE (a pedesis built before
#     issue 51) against this one, both without [transport]: the image counts' cost;
#  2. this event engine without and with [transport] (defaults);
#  3. the soft engine, a WCA fluid of 500 (n = 0.8, Langevin), 20000 steps, without and
#     with [transport].
# Usage: docs/bench/transport_cost.sh BASE_PEDESIS [PEDESIS] [PAIRS]
set -eu
base_bin=$1
bin=${2:-build/pedesis}
pairs=${3:-6}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export OMP_NUM_THREADS=1
cat > "$dir/hs.toml" <<TOML
dimension = 3
dynamics = "event"
seed = 11
[box]
length = 14.0
[[species]]
name = "A"
count = 1372
radius = 0.5
[initial]
positions = "fcc"
[run]
time = 300.0
[output]
log_interval = 50.0
formats = []
progress = false
TOML
cat > "$dir/wca.toml" <<TOML
dimension = 3
dynamics = "langevin"
seed = 41
[box]
length = 8.549879733383484
[[species]]
name = "A"
count = 500
radius = 0.5
[initial]
positions = "random"
min_distance = 0.85
[[force]]
name = "wca"
epsilon = 1.0
sigma = 1.0
[[integrator]]
name = "langevin"
T = 1.0
gamma = 1.0
[neighbor_list]
skin = 0.4
[run]
steps = 20000
dt = 0.004
[output]
log_every = 1000
formats = []
progress = false
TOML
for f in hs wca; do
    cp "$dir/$f.toml" "$dir/${f}_t.toml"
    printf '[transport]\n' >> "$dir/${f}_t.toml"
done
cpu() { # $1 binary, $2 config: user + sys seconds of the whole process
    /usr/bin/time -f "%U %S" "$1" run "$2" --out "$dir/out" --threads 1 2>&1 >/dev/null |
        tail -1 | awk '{print $1 + $2}'
}
compare() { # $1 label, $2 binary A, $3 config A, $4 binary B, $5 config B
    ratios=""
    k=0
    while [ "$k" -lt "$pairs" ]; do
        a=$(cpu "$2" "$3")
        b=$(cpu "$4" "$5")
        ratios="$ratios $(echo "$b $a" | awk '{printf "%.4f", $1 / $2}')"
        k=$((k + 1))
    done
    echo "$ratios" | tr ' ' '\n' | grep . | sort -n | awk -v label="$1" '
        { r[NR] = $1 }
        END { m = (NR % 2) ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2;
              printf "%s: median %.3f, range %.3f to %.3f (%d pairs)\n", label, m, r[1], r[NR], NR }'
}
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
compare "event, image counts (this / base)" "$base_bin" "$dir/hs.toml" "$bin" "$dir/hs.toml"
compare "event, [transport] (with / without)" "$bin" "$dir/hs.toml" "$bin" "$dir/hs_t.toml"
compare "soft WCA, [transport] (with / without)" "$bin" "$dir/wca.toml" "$bin" "$dir/wca_t.toml"
