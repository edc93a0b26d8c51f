#!/usr/bin/env bash
# Fuzzing plcrun with cargo-fuzz (libFuzzer), on the stable toolchain.
#
#   scripts/fuzz.sh build                 install cargo-fuzz if missing, build every target
#   scripts/fuzz.sh seeds                 (re)collect the seed corpora into fuzz/corpus/
#   scripts/fuzz.sh run TARGET [SECONDS]  fuzz one target (default 300 s), one job
#   scripts/fuzz.sh all [SECONDS]         every target, one after the other
#   scripts/fuzz.sh plateau TARGET [MIN] [MAX]
#                                         fuzz one target until its coverage
#                                         plateaus (below), at least MIN s
#                                         (default 300), at most MAX s (1800)
#   scripts/fuzz.sh list                  the targets
#
# Plateau (docs/robustness.md): libFuzzer's edge coverage (`cov:`) grew by
# at most FUZZ_PLATEAU_PERMILLE thousandths (default 5: 0.5 %; 0 asks for
# no new edge at all) during the last quarter of the run, and the run is
# at least MIN seconds long, both counted from the end of the seed corpus
# (INITED). The coverage is sampled every 10 s into
# fuzz/logs/TARGET.curve (seconds, cov, ft, corpus, execs); the fuzzer's
# own output goes to fuzz/logs/TARGET.log, crashes and hangs to
# fuzz/artifacts/TARGET/. FUZZ_TIMEOUT (default 10) is libFuzzer's
# -timeout in seconds; FUZZ_NO_BUILD=1 skips the build.
#
# AddressSanitizer is on for the targets that execute programs (run,
# gen_diff, gen_il_diff, engines_agree): the executor's dispatch, references and string
# operations use `unsafe`. The front-end targets (lex, parse, plcopen, s7,
# check) run only safe Rust, where the sanitizer finds nothing that a
# panic would not, at a quarter of the speed: they are built without it,
# into fuzz/target-nosan/. FUZZ_SANITIZER=address|none sets one sanitizer
# for every target. cargo-fuzz wants a nightly compiler for
# `-Zsanitizer`; RUSTC_BOOTSTRAP=1 lets the stable one accept it (the
# AddressSanitizer runtime ships with stable's rust-std on x86_64 Linux;
# FUZZ_SANITIZER=none where it is missing). Crashes land in
# fuzz/artifacts/TARGET/; turn each into a regression test under
# tests/fuzz_regressions/ (docs/robustness.md, "Fuzzing").
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
export RUSTC_BOOTSTRAP=1
targets=(lex parse plcopen s7 check run gen_diff gen_il_diff engines_agree modbus opcua_write)

# The sanitizer a target is built with (see above).
sanitizer_of() {
    if [ -n "${FUZZ_SANITIZER:-}" ]; then
        echo "$FUZZ_SANITIZER"
        return
    fi
    case "$1" in
        run | gen_diff | gen_il_diff | engines_agree) echo address ;;
        *) echo none ;;
    esac
}

# cargo-fuzz's target directory for a sanitizer (one per sanitizer, so
# that the two builds do not replace each other's binaries).
target_dir_of() {
    case "$(sanitizer_of "$1")" in
        none) echo target-nosan ;;
        *) echo target ;;
    esac
}

ensure_cargo_fuzz() {
    if ! cargo fuzz --version >/dev/null 2>&1; then
        cargo install cargo-fuzz --locked
    fi
}

build() {
    # FUZZ_NO_BUILD=1: use the binaries as they are (a long series of runs
    # while the sources change).
    [ "${FUZZ_NO_BUILD:-0}" = 1 ] && return 0
    ensure_cargo_fuzz
    local list=("$@") t
    [ ${#list[@]} -gt 0 ] || list=("${targets[@]}")
    for t in "${list[@]}"; do
        (cd fuzz && cargo fuzz build -s "$(sanitizer_of "$t")" --codegen-units 16 \
            --target-dir "$(target_dir_of "$t")" "$t")
    done
}

seeds() {
    # The seeds are collected by the smoke test (one implementation,
    # fuzz/src/seeds.rs): programs/, tests/, examples/ and the programs
    # inside the Rust tests.
    PLCRUN_FUZZ_CORPUS="$root/fuzz/corpus" PLCRUN_FUZZ_SECONDS=0 \
        cargo test --test suite fuzz_smoke::every_target_takes_every_seed -- --quiet
}

run() {
    local target=$1 seconds=${2:-300}
    [ -d "fuzz/corpus/$target" ] || mkdir -p "fuzz/corpus/$target"
    # One process (libFuzzer's default; -jobs=1 would do the same with the
    # output in fuzz-0.log): the machine is shared. -rss_limit_mb: the data
    # budget of the targets is 1 MiB, so 2 GiB means a runaway allocation.
    # The generator's input is choices, not text: long inputs from the start.
    (cd fuzz && cargo fuzz run -s "$(sanitizer_of "$target")" --codegen-units 16 \
        --target-dir "$(target_dir_of "$target")" "$target" \
        "corpus/$target" -- -max_total_time="$seconds" \
        -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 $(extra_flags "$target"))
}

# The generators' input is choices, not text: long inputs from the start.
extra_flags() {
    case "$1" in
        gen_diff | gen_il_diff | engines_agree) echo "-len_control=0 -max_len=4096" ;;
    esac
}

# The last `cov: ft: corp:` of a libFuzzer log and its exec count, as
# "execs cov ft corp" (zeros before the first report).
last_stats() {
    grep -a -o '^#[0-9]*[[:space:]]*[A-Za-z]*[[:space:]]*cov: [0-9]* ft: [0-9]* corp: [0-9]*' "$1" \
        | tail -n 1 \
        | sed -E 's/^#([0-9]+)[^c]*cov: ([0-9]+) ft: ([0-9]+) corp: ([0-9]+)/\1 \2 \3 \4/' \
        || true
}

plateau() {
    local target=$1 min=${2:-300} max=${3:-1800}
    local bin="fuzz/$(target_dir_of "$target")/x86_64-unknown-linux-gnu/release/$target"
    local log="fuzz/logs/$target.log" curve="fuzz/logs/$target.curve"
    mkdir -p "fuzz/corpus/$target" "fuzz/artifacts/$target" fuzz/logs
    : >"$curve"
    # The binary itself (not cargo), so that its pid is the fuzzer's: it is
    # stopped with SIGINT, on which libFuzzer prints its final stats.
    # shellcheck disable=SC2046
    "$bin" "fuzz/corpus/$target" -artifact_prefix="fuzz/artifacts/$target/" \
        -max_total_time="$max" -rss_limit_mb=2048 \
        -timeout="${FUZZ_TIMEOUT:-10}" -print_final_stats=1 $(extra_flags "$target") >"$log" 2>&1 &
    local pid=$! start=loading elapsed stats before
    local permille=${FUZZ_PLATEAU_PERMILLE:-5}
    while kill -0 "$pid" 2>/dev/null; do
        sleep 10
        # The clock starts once the seed corpus is loaded (INITED): a
        # slow seed must not pass for a plateau.
        if [ "$start" = loading ]; then
            grep -a -q INITED "$log" && start=$(date +%s)
            continue
        fi
        elapsed=$(($(date +%s) - start))
        stats=$(last_stats "$log")
        [ -n "$stats" ] || continue
        set -- $stats
        echo "$elapsed $2 $3 $4 $1" >>"$curve"
        [ "$elapsed" -ge "$min" ] || continue
        # The edge count when the last quarter began.
        before=$(awk -v t=$((elapsed - elapsed / 4)) '$1 <= t { c = $2 } END { print c + 0 }' "$curve")
        if [ $((1000 * ($2 - before))) -le $((permille * $2)) ]; then
            echo "plateau: cov $before -> $2 over the last quarter of ${elapsed} s"
            kill -INT "$pid"
            break
        fi
    done
    wait "$pid" || true
    grep -a -E '^stat::|^Done|^==[0-9]+== libFuzzer|^SUMMARY|ERROR' "$log" || true
    echo "curve: $curve (seconds cov ft corpus execs)"
}

case "${1:-}" in
    build) build ;;
    seeds) seeds ;;
    run) shift; build "$1"; run "$@" ;;
    plateau) shift; build "$1"; plateau "$@" ;;
    all)
        build
        [ -d fuzz/corpus ] || seeds
        for t in "${targets[@]}"; do run "$t" "${2:-300}"; done
        ;;
    list) printf '%s\n' "${targets[@]}" ;;
    *) sed -n '2,20p' "$0"; exit 2 ;;
esac
