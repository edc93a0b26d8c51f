#!/usr/bin/env bash
# Which PLCopen XML projects load and run: the measurement of issue #29
# (Beremiz, OpenPLC Editor projects), kept in docs/compatibility.md.
#
#   scripts/plcopen_projects.sh [-p PLCRUN] [-n CYCLES] FILE_OR_DIR...
#
# Every `*.xml` file given, or found under a directory given, is checked
# (`plcrun check`) and, when it loads, run for CYCLES cycles (default 100)
# with a 60 s limit. The output is a Markdown table: the project, whether
# it loads, whether it runs, and the codes and names of its first errors
# (an unknown extension type such as `HMI_BOOL` or `python_eval` is named
# there), then a total line. Keep the projects outside the repository: the
# script only reads them.
set -euo pipefail

plcrun=""
cycles=100
while getopts "p:n:" opt; do
    case $opt in
        p) plcrun=$OPTARG ;;
        n) cycles=$OPTARG ;;
        *) echo "usage: $0 [-p PLCRUN] [-n CYCLES] FILE_OR_DIR..." >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -eq 0 ]; then
    echo "usage: $0 [-p PLCRUN] [-n CYCLES] FILE_OR_DIR..." >&2
    exit 2
fi
if [ -z "$plcrun" ]; then
    root=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
    cargo build --quiet --release --manifest-path "$root/Cargo.toml"
    plcrun="${CARGO_TARGET_DIR:-$root/target}/release/plcrun"
fi

files=()
for arg in "$@"; do
    if [ -d "$arg" ]; then
        while IFS= read -r f; do files+=("$f"); done < <(find "$arg" -name '*.xml' | sort)
    else
        files+=("$arg")
    fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
loads=0
runs=0
echo "| project | loads | runs $cycles cycles | first errors |"
echo "|---|---|---|---|"
for f in "${files[@]}"; do
    load=no
    run=-
    if "$plcrun" check "$f" >/dev/null 2>"$work/check"; then
        load=yes
        loads=$((loads + 1))
        if timeout 60 "$plcrun" "$f" --cycles "$cycles" >/dev/null 2>"$work/run"; then
            run=yes
            runs=$((runs + 1))
        else
            run=no
            grep -m1 -E '^(error|fault)' "$work/run" >"$work/check" || true
        fi
    fi
    # Distinct errors, most frequent first: `E203 HMI_BOOL (7)`.
    why=$(grep -oE '^error\[E[0-9]+\]: [^`]*(`[^`]*`)?' "$work/check" \
        | sed -E 's/^error\[(E[0-9]+)\]: [^`]*`?([^`]*)`?$/\1 \2/' \
        | sort | uniq -c | sort -rn | head -3 \
        | awk '{c=$1; $1=""; sub(/^ /, ""); printf "%s%s (%d)", sep, $0, c; sep="; "}' || true)
    echo "| ${f#./} | $load | $run | $why |"
done
echo
echo "$loads of ${#files[@]} load; $runs run $cycles cycles."
