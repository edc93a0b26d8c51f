#!/usr/bin/env bash
# Fuzzing plcrun with cargo-fuzz (libFuzzer), on the stable toolchain.
#
#   scripts/fuzz.sh build                 install cargo-fuzz if missing, build every target
#   scripts/fuzz.sh seeds                 (re)collect the seed corpora into fuzz/corpus/
#   scripts/fuzz.sh run TARGET [SECONDS]  fuzz one target (default 300 s), one job
#   scripts/fuzz.sh all [SECONDS]         every target, one after the other
#   scripts/fuzz.sh list                  the targets
#
# cargo-fuzz wants a nightly compiler for `-Zsanitizer`; RUSTC_BOOTSTRAP=1
# lets the stable one accept it (the AddressSanitizer runtime ships with
# stable's rust-std on x86_64 Linux). FUZZ_SANITIZER=none builds without a
# sanitizer where that runtime is missing. Crashes land in
# fuzz/artifacts/TARGET/; turn each into a regression test under
# tests/fuzz_regressions/ (docs/robustness.md, "Fuzzing").
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
export RUSTC_BOOTSTRAP=1
sanitizer=${FUZZ_SANITIZER:-address}
targets=(lex parse plcopen s7 check run gen_diff)

ensure_cargo_fuzz() {
    if ! cargo fuzz --version >/dev/null 2>&1; then
        cargo install cargo-fuzz --locked
    fi
}

build() {
    ensure_cargo_fuzz
    (cd fuzz && cargo fuzz build -s "$sanitizer" --codegen-units 16 "$@")
}

seeds() {
    # The seeds are collected by the smoke test (one implementation,
    # fuzz/src/seeds.rs): programs/, tests/, examples/ and the programs
    # inside the Rust tests.
    PLCRUN_FUZZ_CORPUS="$root/fuzz/corpus" PLCRUN_FUZZ_SECONDS=0 \
        cargo test --test fuzz_smoke every_target_takes_every_seed -- --quiet
}

run() {
    local target=$1 seconds=${2:-300}
    [ -d "fuzz/corpus/$target" ] || mkdir -p "fuzz/corpus/$target"
    # One process (libFuzzer's default; -jobs=1 would do the same with the
    # output in fuzz-0.log): the machine is shared. -rss_limit_mb: the data
    # budget of the targets is 1 MiB, so 2 GiB means a runaway allocation.
    # The generator's input is choices, not text: long inputs from the start.
    local extra=()
    [ "$target" = gen_diff ] && extra=(-len_control=0 -max_len=4096)
    (cd fuzz && cargo fuzz run -s "$sanitizer" --codegen-units 16 "$target" \
        "corpus/$target" -- -max_total_time="$seconds" \
        -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 "${extra[@]}")
}

case "${1:-}" in
    build) build ;;
    seeds) seeds ;;
    run) shift; build "$1"; run "$@" ;;
    all)
        build
        [ -d fuzz/corpus ] || seeds
        for t in "${targets[@]}"; do run "$t" "${2:-300}"; done
        ;;
    list) printf '%s\n' "${targets[@]}" ;;
    *) sed -n '2,9p' "$0"; exit 2 ;;
esac
