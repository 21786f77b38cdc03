"""Type stubs of the `vcnc` module (built from python/src/lib.rs)."""

import os
from typing import Any, Dict, Iterator, List, Optional, Tuple, Union

__version__: str

Text = Union[str, bytes]
PathArg = Union[str, "os.PathLike[str]", None]

class Error(Exception):
    """Something went wrong inside vcnc (a bug)."""

class ProgramAlarm(Error):
    """The program alarmed: flatten() or time() has no whole answer."""
    alarm: "Diagnostic"

class Diagnostic:
    """An alarm or a warning."""
    @property
    def code(self) -> str: ...
    @property
    def line(self) -> int: ...
    @property
    def column(self) -> int: ...
    @property
    def message(self) -> str: ...
    @property
    def help(self) -> str: ...
    @property
    def file(self) -> Optional[str]: ...
    @property
    def is_warning(self) -> bool: ...

class Result:
    """What check() found."""
    @property
    def ended(self) -> bool: ...
    @property
    def end(self) -> Optional[str]: ...
    @property
    def alarm(self) -> Optional[Diagnostic]: ...
    @property
    def alarms(self) -> List[Diagnostic]: ...
    @property
    def warnings(self) -> List[Diagnostic]: ...
    @property
    def warning_count(self) -> int: ...
    @property
    def cycle_time_s(self) -> float: ...
    @property
    def distance_feed_s(self) -> float: ...
    @property
    def rapid_mm(self) -> float: ...
    @property
    def cut_mm(self) -> float: ...
    @property
    def extents(self) -> Optional[Dict[str, Dict[str, float]]]: ...
    @property
    def tools(self) -> List[int]: ...
    @property
    def holes(self) -> int: ...
    @property
    def spindle_rpm(self) -> Optional[Tuple[float, float]]: ...
    @property
    def waits(self) -> int: ...
    @property
    def diameter_programming(self) -> bool: ...
    @property
    def dialect(self) -> str: ...
    @property
    def machine(self) -> str: ...

class Time:
    """What time() planned."""
    @property
    def total_s(self) -> float: ...
    @property
    def cutting_s(self) -> float: ...
    @property
    def rapid_s(self) -> float: ...
    @property
    def dwell_s(self) -> float: ...
    @property
    def tool_change_s(self) -> float: ...
    @property
    def spindle_s(self) -> float: ...
    @property
    def in_position_s(self) -> float: ...
    @property
    def cutting_mm(self) -> float: ...
    @property
    def rapid_mm(self) -> float: ...
    @property
    def per_tool(self) -> Dict[Optional[int], float]: ...

class Events(Iterator[Dict[str, Any]]):
    """The run's events, lazily, each shaped as `vcnc run --format jsonl`."""
    def __iter__(self) -> "Events": ...
    def __next__(self) -> Dict[str, Any]: ...

def check(
    text: Text,
    dialect: str = "auto",
    machine: PathArg = None,
    tools: PathArg = None,
    program_dir: PathArg = None,
    block_delete: bool = False,
    optional_stop: bool = False,
    keep_going: bool = False,
) -> Result: ...

def events(
    text: Text,
    dialect: str = "auto",
    machine: PathArg = None,
    tools: PathArg = None,
    program_dir: PathArg = None,
    block_delete: bool = False,
    optional_stop: bool = False,
    keep_going: bool = False,
) -> Events: ...

def flatten(
    text: Text,
    dialect: str = "auto",
    machine: PathArg = None,
    tools: PathArg = None,
    program_dir: PathArg = None,
    block_delete: bool = False,
    optional_stop: bool = False,
) -> str: ...

def time(
    text: Text,
    dialect: str = "auto",
    machine: PathArg = None,
    tools: PathArg = None,
    program_dir: PathArg = None,
    block_delete: bool = False,
    optional_stop: bool = False,
) -> Time: ...

def dialects() -> List[str]: ...
