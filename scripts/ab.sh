#!/usr/bin/env bash
# Wall-clock A/B comparison of two plcrun revisions on the benchmark programs.
#
#   scripts/ab.sh [options] REV_A REV_B
#
# Each revision is a commit (anything `git rev-parse` takes) or `WORK`, the
# working tree as it is now (uncommitted changes included). Both are built
# with the release profile, then every benchmark runs with the two binaries
# alternated (A B, then B A, ...), RUNS times each, and the table gives the
# median, min and max wall time of each side and the ratio B / A of the
# medians. The checksum trace of both sides must be identical: a difference
# is printed as DIFFERS and makes the exit status 1.
#
# Options:
#   -n RUNS        runs per binary and benchmark (default 5)
#   -b LIST        comma-separated benchmark names or prefixes (default: all)
#   -s SCALE       multiply every cycle count by SCALE (e.g. 0.1 for a quick look)
#   -c CPU         pin the runs to this CPU with taskset (when present)
#   --bin-a PATH   use this binary for A instead of building REV_A (same for --bin-b)
#   --build-only   build both binaries, print their paths, run nothing
#
# Built binaries are kept in $AB_DIR/bin/<sha> (default ~/.cache/plcrun-ab;
# WORK is rebuilt every time), so comparing against the same revision again costs no build.
# The benchmark programs are read from this checkout, so both binaries run
# the same input whatever their revision holds.
set -euo pipefail
shopt -s inherit_errexit

root=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
# Outside the checkout: a source tree inside it would be taken for a member
# of its cargo workspace.
ab_dir=${AB_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/plcrun-ab}
runs=5
only=""
scale=1
cpu=""
bin_a=""
bin_b=""
build_only=0
revs=()

usage() {
    sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
    exit 2
}

while [ $# -gt 0 ]; do
    case "$1" in
    -n) runs=$2; shift 2 ;;
    -b) only=$2; shift 2 ;;
    -s) scale=$2; shift 2 ;;
    -c) cpu=$2; shift 2 ;;
    --bin-a) bin_a=$2; shift 2 ;;
    --bin-b) bin_b=$2; shift 2 ;;
    --build-only) build_only=1; shift ;;
    -h | --help) usage ;;
    -*) echo "ab.sh: unknown option $1" >&2; usage ;;
    *) revs+=("$1"); shift ;;
    esac
done
[ ${#revs[@]} -eq 2 ] || usage
case "$runs" in '' | *[!0-9]* | 0) echo "ab.sh: -n needs a positive count" >&2; exit 2 ;; esac

# name, program, cycles, traced variable: the figures of the performance issue's table, plus
# the array-of-FB variant and the empty cycle.
benches=(
    "a_bool_logic bench_a_bool_logic.st 600000 checksum"
    "b_int_sieve bench_b_int_sieve.st 20000 checksum"
    "c_fb_unrolled bench_c_fb_unrolled.st 50000 checksum"
    "c_fb_array bench_c_fb_array.st 20000 checksum"
    "d_real_math bench_d_real_math.st 50000 checksum"
    "empty bench_empty.st 5000000 x"
)

# build REV: prints the path of a release plcrun binary of REV.
build() {
    local rev=$1 sha out src
    # A function called in `$(...) || exit` runs without errexit: every
    # step checks its own status, so a failed build never leaves a stale
    # binary under the revision's name.
    if [ "$rev" = WORK ]; then
        (cd "$root" && cargo build --release --quiet --bin plcrun >&2) ||
            { echo "ab.sh: building the working tree failed" >&2; return 1; }
        out="$ab_dir/bin/WORK"
        mkdir -p "$ab_dir/bin" || return 1
        cp "$root/target/release/plcrun" "$out" || return 1
        echo "$out"
        return
    fi
    sha=$(git -C "$root" rev-parse --verify --quiet "$rev^{commit}") ||
        { echo "ab.sh: $rev is not a commit" >&2; exit 2; }
    out="$ab_dir/bin/$sha"
    if [ ! -x "$out" ]; then
        mkdir -p "$ab_dir/bin" || return 1
        # One target directory for every revision (the dependencies are
        # built once; only plcrun itself is rebuilt per revision), so two
        # runs at once take turns: the lock covers the source tree, the
        # build and the copy of its binary.
        (
            flock 9
            src="$ab_dir/src"
            rm -rf "$src" && mkdir -p "$src" || exit 1
            git -C "$root" archive "$sha" | tar -x -C "$src" || exit 1
            echo "ab.sh: building $rev ($sha)" >&2
            (cd "$src" && CARGO_TARGET_DIR="$ab_dir/target" cargo build --release --quiet --bin plcrun >&2) ||
                exit 1
            cp "$ab_dir/target/release/plcrun" "$out.part" && mv "$out.part" "$out"
        ) 9>"$ab_dir/lock" || { echo "ab.sh: building $rev failed" >&2; return 1; }
    fi
    echo "$out"
}

[ -n "$bin_a" ] || bin_a=$(build "${revs[0]}") || exit 1
[ -n "$bin_b" ] || bin_b=$(build "${revs[1]}") || exit 1
if [ "$build_only" = 1 ]; then
    echo "A: $bin_a"
    echo "B: $bin_b"
    exit 0
fi

pin=()
if [ -n "$cpu" ] && command -v taskset >/dev/null; then
    pin=(taskset -c "$cpu")
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# run_once BIN PROGRAM CYCLES VARIABLE OUT: prints the wall time in microseconds.
run_once() {
    local start end
    start=$EPOCHREALTIME
    "${pin[@]}" "$1" "$root/benches/programs/$2" --cycles "$3" \
        --trace "$4" --changes-only --format csv >"$5"
    end=$EPOCHREALTIME
    echo $(( (${end/./} - ${start/./}) ))
}

# stats: reads microseconds, prints "median min max" in seconds.
stats() {
    sort -n | awk '{ v[NR] = $1 }
        END { m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
              printf "%.3f %.3f %.3f\n", m / 1e6, v[1] / 1e6, v[NR] / 1e6 }'
}

selected() {
    [ -z "$only" ] && return 0
    local want
    for want in ${only//,/ }; do
        case "$1" in "$want"*) return 0 ;; esac
    done
    return 1
}

echo "A: ${revs[0]} ($bin_a)"
echo "B: ${revs[1]} ($bin_b)"
echo "runs: $runs per binary, alternated; cycle scale $scale${pin:+; pinned to CPU $cpu}"
echo
printf '%-14s %10s | %7s %7s %7s | %7s %7s %7s | %6s %s\n' \
    bench cycles "A med" min max "B med" min max "B/A" trace
status=0
for entry in "${benches[@]}"; do
    read -r name prog cycles var <<<"$entry"
    selected "$name" || continue
    cycles=$(awk -v c="$cycles" -v s="$scale" 'BEGIN { n = int(c * s); print (n < 1) ? 1 : n }')
    : >"$tmp/a.us"
    : >"$tmp/b.us"
    for ((i = 0; i < runs; i++)); do
        if ((i % 2 == 0)); then order="a b"; else order="b a"; fi
        for side in $order; do
            if [ "$side" = a ]; then bin=$bin_a; else bin=$bin_b; fi
            run_once "$bin" "$prog" "$cycles" "$var" "$tmp/$side.csv" >>"$tmp/$side.us"
        done
    done
    if cmp -s "$tmp/a.csv" "$tmp/b.csv"; then trace=same; else trace=DIFFERS; status=1; fi
    read -r am amin amax < <(stats <"$tmp/a.us")
    read -r bm bmin bmax < <(stats <"$tmp/b.us")
    ratio=$(awk -v a="$am" -v b="$bm" 'BEGIN { printf "%.3f", (a > 0) ? b / a : 0 }')
    printf '%-14s %10s | %7s %7s %7s | %7s %7s %7s | %6s %s\n' \
        "$name" "$cycles" "$am" "$amin" "$amax" "$bm" "$bmin" "$bmax" "$ratio" "$trace"
done
exit $status
