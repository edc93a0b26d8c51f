"""Running cycles, the virtual clock, variables, forcing, the process
image, retain, online change and chart states, from Python."""

import datetime
import threading
import time

import pytest

import plcrun

COUNTER = """PROGRAM Count
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : DINT; END_VAR
IF go THEN n := n + 1; END_IF
END_PROGRAM"""


def test_cycles_advance_the_virtual_clock():
    plc = plcrun.Plc.compile({"c.st": COUNTER}, cycle_time=datetime.timedelta(milliseconds=20))
    plc["go"] = True
    plc.run_cycle()
    plc.run(cycles=9)
    assert plc["n"] == 10
    assert plc.cycle == 10
    assert plc.time == datetime.timedelta(milliseconds=200)
    assert plc.time_ns == 200_000_000
    assert plc.cycle_time == datetime.timedelta(milliseconds=20)


def test_run_releases_the_gil():
    # A tight loop: the program runs long enough per cycle for the other
    # thread to be scheduled many times while Rust runs.
    src = """PROGRAM Busy VAR i, s : DINT; END_VAR
    FOR i := 1 TO 20000 DO s := s + i MOD 7; END_FOR; END_PROGRAM"""
    plc = plcrun.Plc.compile({"b.st": src}, watchdog="0s")
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0)

    t = threading.Thread(target=count)
    t.start()
    try:
        before = len(ticks)
        plc.run(cycles=300)
        during = len(ticks) - before
    finally:
        stop.set()
        t.join()
    assert during > 10, f"the other thread ran {during} times while the PLC ran"


def test_until_runs_in_virtual_time():
    src = """PROGRAM T VAR_INPUT go : BOOL; END_VAR VAR_OUTPUT done : BOOL; END_VAR
    VAR tm : TON; END_VAR tm(IN := go, PT := T#3s); done := tm.Q; END_PROGRAM"""
    plc = plcrun.Plc.compile({"t.st": src}, cycle_time="100ms")
    plc["go"] = True
    took = plc.until("done", timeout="5s")
    # TON sees IN in the cycle at 0 ms and Q in the one at 3 s.
    assert took == datetime.timedelta(seconds=3, milliseconds=100)
    assert plc["done"] is True
    plc["go"] = False
    plc.run_cycle()
    with pytest.raises(TimeoutError, match="within T#1s"):
        plc.until("done", timeout="1s")
    assert plc.until("done", timeout="1s", value=False) == datetime.timedelta(0)


def test_variables_list_types_and_directions():
    src = """PROGRAM Line
    VAR_INPUT start AT %IX0.1 : BOOL; END_VAR
    VAR_OUTPUT motor AT %QX1.7 : BOOL; END_VAR
    VAR n : INT; END_VAR
    VAR CONSTANT k : INT := 1; END_VAR
    INITIAL_STEP Idle : END_STEP
    TRANSITION FROM Idle TO Run := start; END_TRANSITION
    STEP Run : END_STEP
    TRANSITION FROM Run TO Idle := NOT start; END_TRANSITION
    motor := Run.X;
    END_PROGRAM"""
    plc = plcrun.Plc.compile({"line.sfc": src})
    by_path = {v.path: v for v in plc.variables()}
    assert (by_path["start"].type, by_path["start"].direction, by_path["start"].address) == ("BOOL", "input", "%IX0.1")
    assert by_path["motor"].direction == "output"
    assert by_path["n"].direction == "local" and by_path["n"].writable
    assert not by_path["k"].writable
    assert by_path["Run.X"].direction == "step" and not by_path["Run.X"].writable
    # The chart and the process image.
    assert plc.chart_states() == {"Line": []}  # before the first cycle
    plc.run_cycle()
    assert plc.chart_states() == {"Line": ["Idle"]}
    plc.write_image("I", bytes([0b10]))
    plc.run(2)
    assert plc.chart_states() == {"Line": ["Run"]}
    assert plc["start"] is True
    out = plc.image("Q")
    assert isinstance(out, bytearray) and out[1] == 0x80
    with pytest.raises(ValueError):
        plc.write_image("Q", b"\x00")
    with pytest.raises(ValueError, match="do not fit"):
        plc.write_image("I", b"\x00" * 100)


def test_forcing_wins_over_the_program_and_writes():
    plc = plcrun.Plc.compile({"c.st": COUNTER})
    plc["go"] = True
    plc.force("n", 100)
    plc.run(5)
    assert plc["n"] == 100
    plc["n"] = 7  # a soft write: the force wins
    assert plc.forces() == {"n": 100}
    assert plc.unforce("n") is True
    assert plc.unforce("n") is False
    plc.run_cycle()
    assert plc["n"] == 8
    with pytest.raises(plcrun.VariableError):
        plc.force("n", 2**40)


def test_retain_save_and_restore(tmp_path):
    src = """PROGRAM Plant VAR RETAIN starts : INT; END_VAR VAR tick : BOOL; END_VAR
    tick := NOT tick; END_PROGRAM"""
    plc = plcrun.Plc.compile({"plant.st": src})
    assert plc.retained() == [("Plant.starts", "INT", False)]
    plc["starts"] = 5
    plc.run(3)
    path = tmp_path / "plant.json"
    plc.save_retain(path)
    again = plcrun.Plc.compile({"plant.st": src})
    report = again.restore_retain(path)
    assert report["restored"] == 1 and report["cycle"] == 3
    assert again["starts"] == 5 and again["tick"] is False
    again.run_cycle()
    again.reset_warm()
    assert again["starts"] == 5
    changed = plcrun.Plc.compile({"plant.st": src.replace("starts : INT", "starts : DINT")})
    with pytest.raises(plcrun.RetainError, match="changed type"):
        changed.restore_retain(path)
    partial = changed.restore_retain(path, partial=True)
    assert partial["restored"] == 0
    assert partial["changed_type"] == [("Plant.starts", "INT", "DINT")]


def test_online_change_keeps_state():
    v1 = "PROGRAM P VAR t : TON; et : TIME; END_VAR t(IN := TRUE, PT := T#1s); et := t.ET; END_PROGRAM"
    v2 = v1.replace("et : TIME;", "et : TIME; late : BOOL;").replace("et := t.ET;", "et := t.ET; late := et > T#500ms;")
    plc = plcrun.Plc.compile({"p.st": v1})
    plc.run(30)
    assert plc["et"] == datetime.timedelta(milliseconds=290)
    report = plc.online_change({"p.st": v2})
    assert report["initialised"] == ["P.late"]
    assert "P.t" in report["kept"]
    plc.run_cycle()
    assert plc["et"] == datetime.timedelta(milliseconds=300)
    assert plc["late"] is False
    with pytest.raises(plcrun.CompileError):
        plc.online_change({"p.st": "PROGRAM P x := ; END_PROGRAM"})
    plc.run_cycle()
    assert plc["et"] == datetime.timedelta(milliseconds=310)


def test_chariot_chart_states(repo):
    plc = plcrun.Plc.compile(repo / "programs" / "chariot.sfc")
    plc.run_cycle()
    assert plc.chart_states() == {"CHARIOT": ["INIT"]}
    plc["FcA"] = True
    plc["Dcy"] = True
    plc.run(2)
    assert plc.chart_states() == {"CHARIOT": ["AV"]}
    assert plc["KMAV"] is True
