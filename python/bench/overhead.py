"""Per-call overhead of the Python face: `plc["x"]` reads and writes,
`run_cycle()`, against `run(cycles=N)` (one call for N cycles) and a
session run with a Python callback. Prints nanoseconds per call (the best
of 5 repeats of timeit). Run it with a release build installed:

    pip install ./python && python python/bench/overhead.py
"""

import timeit

import plcrun

# A tiny program: the cycle itself costs little, so what is measured is
# the crossing between Python and Rust.
SOURCE = """PROGRAM Tiny
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT y : INT; on : BOOL; END_VAR
y := x + 1; on := y > 10;
END_PROGRAM"""


def best_ns(stmt, number, setup_globals):
    times = timeit.repeat(stmt, number=number, repeat=5, globals=setup_globals)
    return min(times) / number * 1e9


def main():
    plc = plcrun.Plc.compile({"tiny.st": SOURCE})
    g = {"plc": plc}
    n = 200_000
    rows = [
        ('plc["y"]  (INT read)', best_ns('plc["y"]', n, g)),
        ('plc["on"] (BOOL read)', best_ns('plc["on"]', n, g)),
        ('plc["x"] = 5  (INT write)', best_ns('plc["x"] = 5', n, g)),
        ("plc.run_cycle()", best_ns("plc.run_cycle()", n, g)),
        ("plc.run(cycles=10000) / 10000", best_ns("plc.run(cycles=10000)", 20, g) / 10_000),
        (
            "plc.simulate(10000, on_cycle=f) / 10000",
            best_ns("plc.simulate(10000, trace=['y'], on_cycle=lambda p: None)", 5, g) / 10_000,
        ),
    ]
    width = max(len(r[0]) for r in rows)
    for name, ns in rows:
        print(f"{name:<{width}}  {ns:8.0f} ns")


if __name__ == "__main__":
    main()
