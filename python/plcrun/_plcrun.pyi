"""Type stubs of the compiled module ``plcrun._plcrun`` (see ``plcrun``)."""

import datetime
import os
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

__version__: str

PathLike = Union[str, os.PathLike]
Sources = Union[PathLike, Sequence[PathLike], Mapping[str, str]]
Duration = Union[str, datetime.timedelta]
PyValue = Union[bool, int, float, str, datetime.timedelta, datetime.date, datetime.time, datetime.datetime]

class PlcError(Exception):
    """Base class of every error plcrun raises."""

class CompileError(PlcError):
    """The sources do not compile."""

    diagnostics: List[Diagnostic]

class RuntimeFault(PlcError):
    """The program faulted in a cycle; the PLC stays faulted until a reset."""

    code: str
    kind: str
    instance: str
    pou: str
    location: str
    file: str
    line: int
    column: int
    cycle: int

class VariableError(PlcError):
    """A variable cannot be read or written."""

    path: str

class StimulusError(PlcError):
    """A stimulus cannot be applied to the program."""

class RetainError(PlcError):
    """A retain file cannot be written or does not fit the program."""

class Diagnostic:
    """One diagnostic of the compiler."""

    code: str
    severity: Literal["error", "warning"]
    file: str
    line: int
    column: int
    message: str
    notes: List[str]

class Variable:
    """One variable as ``Plc.variables()`` lists it."""

    path: str
    type: str
    direction: Literal["input", "output", "local", "global", "step", "action"]
    address: Optional[str]
    writable: bool
    values: List[str]

class StTest:
    """One unit test written in IEC and its outcome."""

    name: str
    file: str
    outcome: Literal["passed", "failed", "errored", "skipped"]
    cycles: int
    assertions: int
    seconds: float
    failures: List[str]
    output: List[str]
    fault: Optional[RuntimeFault]
    def report(self) -> str: ...

class Plc:
    """A compiled IEC 61131-3 program running on a virtual clock."""

    @staticmethod
    def compile(
        sources: Sources,
        *,
        cycle_time: Optional[Duration] = None,
        program: Optional[str] = None,
        watchdog: Optional[Duration] = None,
        strict: bool = False,
        grafcet: bool = False,
        addressing: Optional[Literal["iec", "openplc", "byte"]] = None,
    ) -> Plc: ...
    def run_cycle(self) -> None: ...
    def run(self, cycles: int = 1) -> None: ...
    def scan(self, n: int = 1) -> None: ...
    def until(self, name: str, timeout: Duration, value: Optional[PyValue] = None) -> datetime.timedelta: ...
    def __getitem__(self, name: str) -> Any: ...
    def __setitem__(self, name: str, value: PyValue) -> None: ...
    def __contains__(self, name: str) -> bool: ...
    def get(self, name: str, default: Any = None) -> Any: ...
    def literal(self, name: str) -> str: ...
    @property
    def cycle(self) -> int: ...
    @property
    def time(self) -> datetime.timedelta: ...
    @property
    def time_ns(self) -> int: ...
    @property
    def cycle_time(self) -> datetime.timedelta: ...
    @property
    def warnings(self) -> List[Diagnostic]: ...
    def variables(self) -> List[Variable]: ...
    def force(self, name: str, value: PyValue) -> None: ...
    def unforce(self, name: str) -> bool: ...
    def unforce_all(self) -> None: ...
    def forces(self) -> Dict[str, Any]: ...
    def image(self, area: str) -> bytearray: ...
    def write_image(self, area: str, data: Union[bytes, bytearray, memoryview, Sequence[int]], offset: int = 0) -> None: ...
    def chart_states(self) -> Dict[str, List[str]]: ...
    def retained(self) -> List[Tuple[str, str, bool]]: ...
    def save_retain(self, path: PathLike) -> None: ...
    def restore_retain(self, path: PathLike, partial: bool = False) -> Dict[str, Any]: ...
    def reset_warm(self) -> None: ...
    def reset_cold(self) -> None: ...
    def online_change(
        self,
        sources: Sources,
        *,
        cycle_time: Optional[Duration] = None,
        program: Optional[str] = None,
        watchdog: Optional[Duration] = None,
        strict: bool = False,
        grafcet: bool = False,
        addressing: Optional[Literal["iec", "openplc", "byte"]] = None,
    ) -> Dict[str, List[Any]]: ...
    def default_trace(self) -> List[str]: ...
    def simulate(
        self,
        cycles: int,
        stimulus: Optional[Union[Mapping[str, Sequence[Any]], Any]] = None,
        *,
        csv: Optional[str] = None,
        trace: Optional[Sequence[str]] = None,
        on_cycle: Optional[Callable[[Plc], Optional[bool]]] = None,
        output: Literal["dict", "numpy", "pandas"] = "dict",
    ) -> Any: ...

def run_st_tests(
    sources: Sources,
    *,
    cycle_time: Optional[Duration] = None,
    watchdog: Optional[Duration] = None,
    filter: Optional[str] = None,
    strict: bool = False,
) -> List[StTest]: ...

class ComparePair:
    """Two programs paired as ``plcrun compare A -- B`` pairs them (see
    ``plcrun.campaign``)."""

    def __init__(
        self,
        a: Sources,
        b: Sources,
        *,
        a_label: str,
        b_label: str,
        cycles: int,
        cycle_time: Optional[Duration] = None,
        program_a: Optional[str] = None,
        program_b: Optional[str] = None,
        map: Sequence[str] = ...,
        ignore: Sequence[str] = ...,
        lag: int = 0,
        change_prob: float = 0.1,
        min_hold: int = 1,
        max_hold: int = 20,
    ) -> None: ...
    def run_seeds(self, start: int, stop: int) -> Tuple[List[int], int]: ...
    def report(self, start: int, stop: int, differing: List[int]) -> str: ...
