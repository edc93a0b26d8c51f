"""Session runs: stimulus as CSV, dict or DataFrame, the trace as a dict,
NumPy arrays or a DataFrame, and a per-cycle callback."""

import csv
import datetime

import pytest

import plcrun

ALG01_TRACE = ["M0", "M1", "M2", "M3", "M4", "V1", "V2", "L1"]


def _expected(path):
    """The rows of a golden trace as literals, keyed like the CSV."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def _as_literals(trace, names):
    rows = []
    for k, cycle in enumerate(trace["cycle"]):
        row = {"cycle": str(cycle)}
        for n in names:
            row[n] = "TRUE" if trace[n][k] else "FALSE"
        rows.append(row)
    return rows


def test_csv_stimulus_gives_the_golden_trace(repo):
    plc = plcrun.Plc.compile(repo / "programs" / "alg01.il")
    trace = plc.simulate(1200, csv=str(repo / "programs" / "alg01_s1.csv"), trace=ALG01_TRACE)
    expected = _expected(repo / "programs" / "alg01_s1.expected.csv")
    assert len(trace["cycle"]) == 1200
    assert trace["time"][3] == datetime.timedelta(milliseconds=30)
    got = _as_literals(trace, ALG01_TRACE)
    assert got == [{k: r[k] for k in ["cycle"] + ALG01_TRACE} for r in expected]


def test_dict_stimulus_is_the_same_as_the_csv(repo):
    # The CSV's rows as a dict of lists, one entry per cycle; None leaves
    # the input unchanged.
    rows = list(csv.DictReader(open(repo / "programs" / "alg01_s1.csv", newline="")))
    stim = {"cycle": [int(r["cycle"]) for r in rows]}
    for col in ["SW1", "S1", "S2"]:
        stim[col] = [None if r[col] == "" else r[col] == "TRUE" for r in rows]
    by_csv = plcrun.Plc.compile(repo / "programs" / "alg01.il").simulate(
        1200, csv=str(repo / "programs" / "alg01_s1.csv"), trace=ALG01_TRACE
    )
    by_dict = plcrun.Plc.compile(repo / "programs" / "alg01.il").simulate(1200, stim, trace=ALG01_TRACE)
    assert by_dict == by_csv


def test_rows_without_a_key_are_one_per_cycle_from_now():
    src = "PROGRAM P VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR y := 2 * x; END_PROGRAM"
    plc = plcrun.Plc.compile({"p.st": src})
    plc.run(5)
    trace = plc.simulate(4, {"x": [1, None, 3, float("nan")]}, trace=["y"])
    assert trace["cycle"] == [5, 6, 7, 8]
    assert trace["y"] == [2, 2, 6, 6]
    # A later run does not replay the old stimulus.
    plc["x"] = 10
    assert plc.simulate(1, trace=["y"])["y"] == [20]


def test_time_keyed_stimulus():
    src = "PROGRAM P VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR y := x; END_PROGRAM"
    plc = plcrun.Plc.compile({"p.st": src}, cycle_time="10ms")
    trace = plc.simulate(5, {"time": ["20ms", datetime.timedelta(milliseconds=40)], "x": [1, 2]}, trace=["y"])
    assert trace["y"] == [0, 0, 1, 1, 2]


def test_bad_stimuli_are_refused():
    src = "PROGRAM P VAR_INPUT x : INT; b : BOOL; END_VAR END_PROGRAM"
    plc = plcrun.Plc.compile({"p.st": src})
    with pytest.raises(plcrun.StimulusError, match="rows"):
        plc.simulate(3, {"x": [1, 2], "b": [True]})
    with pytest.raises(plcrun.StimulusError, match="row 1"):
        plc.simulate(3, {"x": [1, 99999]})
    with pytest.raises(plcrun.VariableError):
        plc.simulate(3, {"nope": [1]})
    with pytest.raises(plcrun.StimulusError):
        plc.simulate(3, {"cycle": [2, 1], "x": [1, 2]})
    with pytest.raises(plcrun.StimulusError):
        plc.simulate(3, csv="cycle,x\n0,notanumber\n")
    with pytest.raises(ValueError):
        plc.simulate(3, output="excel")
    assert plc.cycle == 0


def test_callback_closes_the_loop():
    # A tank: the program opens the valve below 40, the plant (Python)
    # fills 3 per cycle while open and drains 1 per cycle.
    src = """PROGRAM Tank VAR_INPUT level : INT; END_VAR VAR_OUTPUT valve : BOOL; END_VAR
    IF level < 40 THEN valve := TRUE; ELSIF level > 60 THEN valve := FALSE; END_IF;
    END_PROGRAM"""
    plc = plcrun.Plc.compile({"tank.st": src})

    def plant(p):
        p["level"] = p["level"] + (3 if p["valve"] else 0) - 1

    trace = plc.simulate(200, trace=["level", "valve"], on_cycle=plant)
    assert min(trace["level"][50:]) >= 38 and max(trace["level"][50:]) <= 63
    assert True in trace["valve"] and False in trace["valve"]

    # Returning False stops the run.
    stopped = plc.simulate(100, trace=["level"], on_cycle=lambda p: p.cycle < 210)
    assert stopped["cycle"][-1] == 209


def test_callback_errors_propagate():
    plc = plcrun.Plc.compile({"p.st": "PROGRAM P VAR x : INT; END_VAR END_PROGRAM"})

    def broken(p):
        raise RuntimeError("plant model failed")

    with pytest.raises(RuntimeError, match="plant model failed"):
        plc.simulate(5, on_cycle=broken)
    assert plc.cycle == 1


def test_numpy_and_pandas_outputs():
    np = pytest.importorskip("numpy")
    src = "PROGRAM P VAR_OUTPUT n : INT; r : LREAL; END_VAR n := n + 1; r := n / 2.0; END_PROGRAM"
    arrays = plcrun.Plc.compile({"p.st": src}).simulate(4, output="numpy")
    assert arrays["n"].tolist() == [1, 2, 3, 4]
    assert arrays["r"].dtype == np.float64
    assert arrays["time"][1] == np.timedelta64(10, "ms")
    pd = pytest.importorskip("pandas")
    frame = plcrun.Plc.compile({"p.st": src}).simulate(4, output="pandas")
    assert list(frame.columns) == ["cycle", "time", "n", "r"]
    stim = pd.DataFrame({"n": [10, 20]})
    again = plcrun.Plc.compile({"p.st": src}).simulate(2, stim, trace=["n"])
    assert again["n"] == [11, 21]
