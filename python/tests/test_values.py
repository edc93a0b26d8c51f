"""Python values in and out of PLC variables, through the library's own
literal decoding (range checks, subranges, enumerations)."""

import datetime

import pytest

import plcrun

TYPES = """
TYPE Color : (Red, Green, Blue); END_TYPE
TYPE Percent : INT (0..100); END_TYPE
PROGRAM P
VAR_INPUT
  b : BOOL; i : INT; si : SINT; u : ULINT; w : WORD; r : REAL; lr : LREAL;
  t : TIME; d : DATE; tod1 : TOD; dt1 : DT; s : STRING; ws : WSTRING; ch : CHAR;
  c : Color; pct : Percent;
END_VAR
VAR CONSTANT k : INT := 3; END_VAR
END_PROGRAM
"""


@pytest.fixture
def plc():
    return plcrun.Plc.compile({"types.st": TYPES})


@pytest.mark.parametrize(
    "name, value",
    [
        ("b", True),
        ("b", False),
        ("i", -32768),
        ("i", 32767),
        ("si", -128),
        ("u", 2**64 - 1),
        ("w", 0xBEEF),
        ("r", 0.1),
        ("lr", 1e-300),
        ("t", datetime.timedelta(minutes=1, milliseconds=5)),
        ("t", -datetime.timedelta(milliseconds=250)),
        ("d", datetime.date(2024, 2, 29)),
        ("tod1", datetime.time(23, 59, 59, 999000)),
        ("dt1", datetime.datetime(1999, 12, 31, 12, 0, 0, 500)),
        ("s", "it's 5$ \"quoted\"\n"),
        ("ws", "süß €"),
        ("ch", "x"),
        ("c", "Blue"),
        ("pct", 100),
    ],
)
def test_values_round_trip(plc, name, value):
    plc[name] = value
    got = plc[name]
    assert type(got) is type(value)
    assert got == value


def test_initial_values_and_literals(plc):
    assert plc["b"] is False
    assert plc["k"] == 3
    assert plc["c"] == "Red"
    plc["w"] = 255
    assert plc.literal("w") == "16#FF"


def test_a_str_is_an_iec_literal_for_other_types(plc):
    plc["t"] = "T#1.5s"
    assert plc["t"] == datetime.timedelta(seconds=1.5)
    plc["w"] = "16#10"
    assert plc["w"] == 16
    plc["c"] = "Color#Green"
    assert plc["c"] == "Green"


@pytest.mark.parametrize(
    "name, value",
    [("i", 32768), ("i", -32769), ("si", 200), ("u", -1), ("w", 65536), ("pct", 101), ("c", "Purple")],
)
def test_values_out_of_range_are_refused(plc, name, value):
    with pytest.raises(plcrun.VariableError) as e:
        plc[name] = value
    assert e.value.path == name
    assert plc[name] != value


@pytest.mark.parametrize(
    "name, value",
    [("i", 1.5), ("i", True), ("b", 1), ("r", True), ("t", 5), ("d", 3), ("ch", "xy"), ("s", 3)],
)
def test_values_of_the_wrong_python_type_are_refused(plc, name, value):
    with pytest.raises(TypeError):
        plc[name] = value


def test_non_finite_reals_are_refused(plc):
    with pytest.raises(plcrun.VariableError):
        plc["r"] = float("inf")


def test_constants_cannot_be_written(plc):
    with pytest.raises(plcrun.VariableError, match="k"):
        plc["k"] = 4
    assert plc["k"] == 3


def test_unknown_names(plc):
    with pytest.raises(plcrun.VariableError, match="unknown variable `nope`") as e:
        plc["nope"]
    assert e.value.path == "nope"
    assert "nope" not in plc and "i" in plc
    assert plc.get("nope", 7) == 7
