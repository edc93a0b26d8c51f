"""Typed exceptions: compile diagnostics, runtime faults with their place."""

import pytest

import plcrun


def test_compile_error_lists_every_diagnostic_with_its_position():
    src = "PROGRAM B\nVAR y : INT; END_VAR\nx := 1;\ny := TRUE;\nEND_PROGRAM\n"
    with pytest.raises(plcrun.CompileError) as e:
        plcrun.Plc.compile({"b.st": src})
    diags = e.value.diagnostics
    assert [(d.code, d.file, d.line, d.column, d.severity) for d in diags][0] == ("E201", "b.st", 3, 1, "error")
    assert len([d for d in diags if d.severity == "error"]) == 2
    assert "undeclared variable `x`" in diags[0].message
    assert str(diags[0]).startswith("b.st:3:1: error[E201]")
    assert isinstance(e.value, plcrun.PlcError)
    assert "E201" in str(e.value)


def test_unreadable_files_are_os_errors(tmp_path):
    with pytest.raises(OSError):
        plcrun.Plc.compile(tmp_path / "missing.st")


def test_runtime_fault_names_code_instance_and_place():
    src = """FUNCTION_BLOCK Div VAR_INPUT a, b : INT; END_VAR VAR_OUTPUT q : INT; END_VAR
q := a / b;
END_FUNCTION_BLOCK
PROGRAM P VAR d : ARRAY[1..2] OF Div; END_VAR
d[1](a := 4, b := 2);
d[2](a := 1, b := 0);
END_PROGRAM"""
    plc = plcrun.Plc.compile({"p.st": src})
    with pytest.raises(plcrun.RuntimeFault) as e:
        plc.run_cycle()
    f = e.value
    assert (f.code, f.instance, f.pou, f.file, f.line, f.cycle) == ("R001", "P.d[2]", "Div", "p.st", 2, 0)
    assert f.kind == "division by zero"
    # Faulted until a reset.
    with pytest.raises(plcrun.RuntimeFault):
        plc.run(3)
    assert plc["d[1].q"] == 2
    plc.reset_cold()
    assert plc["d[1].q"] == 0


def test_bad_options_are_value_errors():
    with pytest.raises(ValueError, match="cycle_time"):
        plcrun.Plc.compile({"p.st": "PROGRAM P END_PROGRAM"}, cycle_time="10 parsecs")
    with pytest.raises(ValueError, match="positive"):
        plcrun.Plc.compile({"p.st": "PROGRAM P END_PROGRAM"}, cycle_time="0ms")
    with pytest.raises(TypeError):
        plcrun.Plc.compile({"p.st": "PROGRAM P END_PROGRAM"}, cycle_time=10)
    with pytest.raises(ValueError):
        plcrun.Plc.compile({"p.st": "PROGRAM P END_PROGRAM"}, addressing="octal")
    with pytest.raises(TypeError):
        plcrun.Plc.compile(42)


def test_several_programs_need_a_choice():
    src = "PROGRAM A VAR x : INT; END_VAR x := 1; END_PROGRAM PROGRAM B VAR x : INT; END_VAR x := 2; END_PROGRAM"
    with pytest.raises(plcrun.CompileError):
        plcrun.Plc.compile({"ab.st": src})
    plc = plcrun.Plc.compile({"ab.st": src}, program="B")
    plc.run_cycle()
    assert plc["x"] == 2
