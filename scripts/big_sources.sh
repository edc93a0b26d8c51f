#!/usr/bin/env bash
# 50 MB sources through `plcrun check` (release build), with wall time,
# CPU time and peak memory from /usr/bin/time -v (docs/robustness.md,
# "50 MB sources").
#
#   scripts/big_sources.sh [MB] [SHAPE...]
#
# MB defaults to 50. Shapes (default: all three):
#   pous   many small POUs: function blocks of a few statements, a program
#          calling some of them
#   huge   one PROGRAM of statements, one statement a line
#   line   the same statements on one line
# The sources are written to $TMPDIR (removed afterwards); PLCRUN_BIN
# names another binary than target/release/plcrun.
set -euo pipefail
cd "$(dirname "$0")/.."
mb=${1:-50}
shift || true
shapes=("$@")
[ ${#shapes[@]} -gt 0 ] || shapes=(pous huge line)
bin=${PLCRUN_BIN:-target/release/plcrun}
[ -x "$bin" ] || cargo build --release --bin plcrun
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

generate() {
    python3 - "$1" "$2" "$3" <<'EOF'
import sys
shape, mb, path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
size = mb * 1_000_000
with open(path, "w") as f:
    n = 0
    if shape == "pous":
        i = 0
        while n < size:
            t = (f"FUNCTION_BLOCK FB{i}\nVAR_INPUT a : DINT; END_VAR\n"
                 f"VAR_OUTPUT q : DINT; END_VAR\nVAR k : DINT; END_VAR\n"
                 f"k := k + a;\nIF k > 100 THEN k := 0; END_IF;\nq := k * 2 + {i % 97};\n"
                 f"END_FUNCTION_BLOCK\n")
            f.write(t)
            n += len(t)
            i += 1
        calls = min(i, 1000)
        f.write("PROGRAM Main\nVAR\n")
        f.write("".join(f"  f{j} : FB{j};\n" for j in range(calls)))
        f.write("  total : DINT;\nEND_VAR\n")
        f.write("".join(f"f{j}(a := {j}); total := total + f{j}.q;\n" for j in range(calls)))
        f.write("END_PROGRAM\n")
    else:
        end = " " if shape == "line" else "\n"
        f.write("PROGRAM Main\nVAR x : DINT; y : BOOL; END_VAR\n")
        stmt = "x := x + 1; y := y OR (x > 10);" + end
        while n < size:
            f.write(stmt)
            n += len(stmt)
        f.write("\nEND_PROGRAM\n")
EOF
}

printf '%-6s %8s %10s %8s %8s %12s %s\n' shape MB lines wall_s user_s max_rss_MB exit
for shape in "${shapes[@]}"; do
    src="$tmp/$shape.st"
    generate "$shape" "$mb" "$src"
    bytes=$(stat -c %s "$src")
    lines=$(wc -l <"$src")
    set +e
    /usr/bin/time -v "$bin" check "$src" >"$tmp/out" 2>"$tmp/time"
    code=$?
    set -e
    wall=$(grep 'Elapsed (wall clock)' "$tmp/time" | awk '{print $NF}')
    user=$(grep 'User time' "$tmp/time" | awk '{print $NF}')
    rss=$(grep 'Maximum resident' "$tmp/time" | awk '{print int($NF / 1024)}')
    printf '%-6s %8.1f %10s %8s %8s %12s %s\n' "$shape" "$(awk "BEGIN{print $bytes / 1000000}")" \
        "$lines" "$wall" "$user" "$rss" "$code"
    grep -m 3 -E '^(error|warning)|E[0-9]{3}' "$tmp/out" "$tmp/time" || true
    rm -f "$src"
done
