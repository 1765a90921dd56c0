# Shared by the side-by-side benchmark scripts in this directory (sourced, not run).
# The caller sets `prog` (its name, for messages) and `repo_root` before sourcing.

die() { echo "$prog: error: $*" >&2; exit 1; }
note() { echo "$prog: $*" >&2; }

is_uint() { [[ $1 =~ ^[0-9]+$ ]]; }
is_num() { [[ $1 =~ ^[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?$ || $1 =~ ^\.[0-9]+$ ]]; }

# median of the numbers on standard input ("nan" when there are none)
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) { print "nan"; exit } print (NR % 2) ? v[(NR + 1) / 2] : 0.5 * (v[NR / 2] + v[NR / 2 + 1]) }'; }

# value after the key of GNU time's -v report: time_field KEY-REGEX FILE
time_field() { awk -F': ' -v k="$1" '$1 ~ k { print $2; exit }' "$2"; }

# make_scratch PREFIX: sets SCRATCH (a new mktemp directory unless SCRATCH was given)
# and created_scratch; refuses a directory inside the repository, checked before
# anything is created (the deepest existing ancestor is resolved) and after.
make_scratch() {
    created_scratch=0
    if [[ -z ${SCRATCH:-} ]]; then
        SCRATCH=$(mktemp -d "${TMPDIR:-/tmp}/$1.XXXXXX")
        created_scratch=1
    else
        local probe=$SCRATCH rest=""
        while [[ ! -d $probe ]]; do rest="/$(basename -- "$probe")$rest"; probe=$(dirname -- "$probe"); done
        case "$(cd "$probe" && pwd -P)$rest" in
            "$repo_root" | "$repo_root"/*) die "SCRATCH must lie outside the repository ($repo_root)" ;;
        esac
        mkdir -p "$SCRATCH"
    fi
    SCRATCH=$(cd "$SCRATCH" && pwd -P)
    case "$SCRATCH" in
        "$repo_root" | "$repo_root"/*) die "SCRATCH must lie outside the repository ($repo_root)" ;;
    esac
    trap cleanup_scratch EXIT
}

# On exit: keep the scratch directory (KEEP_SCRATCH=1), remove it if make_scratch made
# it, or else remove only the entries named in scratch_entries (relative to it).
scratch_entries=()
cleanup_scratch() {
    if [[ ${KEEP_SCRATCH:-0} == 1 ]]; then
        note "scratch kept: $SCRATCH"
    elif [[ $created_scratch == 1 ]]; then
        rm -rf -- "$SCRATCH"
    else
        local e
        for e in "${scratch_entries[@]}"; do rm -rf -- "${SCRATCH:?}/$e"; done
    fi
}

# describe_pedesis BINARY: sets cpu, ped_rev, ped_dirty and ped_flags (the build type and
# its flags from the CMake cache next to the binary) for a benchmark's header
describe_pedesis() {
    cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
    ped_rev=$(git -C "$repo_root" rev-parse --short HEAD 2>/dev/null || echo unknown)
    ped_dirty=$(git -C "$repo_root" status --porcelain --untracked-files=no 2>/dev/null | grep -q . && echo " (+ local changes)" || true)
    ped_flags=""
    local cache bt fl
    cache="$(dirname "$1")/CMakeCache.txt"
    if [[ -f $cache ]]; then
        bt=$(sed -n 's/^CMAKE_BUILD_TYPE:STRING=//p' "$cache")
        fl=$(sed -n "s/^CMAKE_CXX_FLAGS_${bt^^}:STRING=//p" "$cache" 2>/dev/null || true)
        ped_flags="$bt${fl:+ ($fl)}"
    fi
}
