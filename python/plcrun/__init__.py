"""plcrun: an IEC 61131-3 runtime (IL, ST, SFC) on a virtual clock.

Compile a program and run it cycle by cycle, reading and writing its
variables with Python values::

    import plcrun

    plc = plcrun.Plc.compile({"tank.st": '''
        PROGRAM Tank
        VAR_INPUT level : INT; END_VAR
        VAR_OUTPUT pump : BOOL; END_VAR
        pump := level < 20;
        END_PROGRAM'''}, cycle_time="10ms")
    plc["level"] = 12
    plc.run_cycle()
    assert plc["pump"] is True

Values: BOOL is ``bool``; integers and bit strings ``int`` (range-checked
on writes); REAL and LREAL ``float``; TIME ``datetime.timedelta``; DATE,
TIME_OF_DAY and DATE_AND_TIME ``datetime.date``, ``datetime.time`` and
``datetime.datetime``; strings, characters and enumeration values ``str``.
A ``str`` written to a variable that is not a string is read as an IEC
literal (``plc["t"] = "T#1.5s"``).

Errors: ``CompileError`` (``.diagnostics``), ``RuntimeFault`` (``.code``,
``.instance``, ...), ``VariableError`` (``.path``), ``StimulusError``,
``RetainError``; all derive from ``PlcError``.

``run_st_tests`` runs unit tests written in IEC (``TEST_`` POUs), and the
pytest plugin (``plcrun.pytest_plugin``, registered on install) gives a
``plc`` fixture and collects ST test files. ``plcrun.campaign`` runs
``plcrun compare`` over many seeds through any executor (a process pool,
Dask). The guide is docs/python.md.
"""

from ._plcrun import (
    CompileError,
    ComparePair,
    Diagnostic,
    Plc,
    PlcError,
    RetainError,
    RuntimeFault,
    StimulusError,
    StTest,
    Variable,
    VariableError,
    __version__,
    run_st_tests,
)

__all__ = [
    "CompileError",
    "ComparePair",
    "Diagnostic",
    "Plc",
    "PlcError",
    "RetainError",
    "RuntimeFault",
    "StimulusError",
    "StTest",
    "Variable",
    "VariableError",
    "__version__",
    "run_st_tests",
]
