"""Type stubs of the native module rdem._rdem (see the package docstring)."""

from typing import Callable, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

class RdemError(Exception):
    """An rdem command failed."""

    file: Optional[str]
    """The script file (``<command>`` or ``<commands>`` for text given from Python)."""
    line: Optional[int]
    """1-based line of the word the error points at."""
    column: Optional[int]
    """1-based column (in characters) of that word."""
    message: str
    """The message alone."""
    report: str
    """The whole report, with the script excerpt and the caret, as the rdem command prints it."""

class _Readers:
    @property
    def x(self) -> npt.NDArray[np.float64]:
        """Positions of the owned particles (n x 3 copy, storage order)."""
    @property
    def v(self) -> npt.NDArray[np.float64]:
        """Velocities (n x 3 copy)."""
    @property
    def omega(self) -> npt.NDArray[np.float64]:
        """Angular velocities (n x 3 copy)."""
    @property
    def f(self) -> npt.NDArray[np.float64]:
        """Forces of the last step (n x 3 copy)."""
    @property
    def torque(self) -> npt.NDArray[np.float64]:
        """Torques of the last step (n x 3 copy)."""
    @property
    def radius(self) -> npt.NDArray[np.float64]:
        """Radii (copy)."""
    @property
    def mass(self) -> npt.NDArray[np.float64]:
        """Masses (copy)."""
    @property
    def tag(self) -> npt.NDArray[np.uint64]:
        """Particle IDs (copy): which particle each row of the other arrays is."""
    @property
    def type(self) -> npt.NDArray[np.uint32]:
        """Particle types (copy)."""
    def array(self, name: str) -> npt.NDArray[np.float64]:
        """A copy of any per-particle array by name (named properties too; width > 1: n x width)."""
    @property
    def thermo(self) -> dict[str, npt.NDArray[np.float64]]:
        """The thermo rows of the current or last run: {keyword: column}."""
    def variable(self, name: str) -> Union[float, npt.NDArray[np.float64], str]:
        """A variable's value: float (equal style), array (atom style) or text (other styles)."""
    def compute(self, id: str, index: Optional[int] = None) -> float:
        """A compute's global scalar, or its value ``index`` (1-based)."""
    def compute_peratom(self, id: str, column: Optional[int] = None) -> npt.NDArray[np.float64]:
        """A per-particle compute (or its column, 1-based), in storage order."""
    def fix(self, id: str, index: Optional[int] = None) -> float:
        """A fix's global scalar, or its value ``index`` (1-based)."""
    def fix_peratom(self, id: str, column: Optional[int] = None) -> npt.NDArray[np.float64]:
        """A per-particle fix value (or its column, 1-based), in storage order."""
    @property
    def step(self) -> int:
        """The current step."""
    @property
    def time(self) -> float:
        """The simulated time."""
    @property
    def natoms(self) -> int:
        """The number of particles."""

class StepView(_Readers):
    """The simulation as a callback sees it; valid during the call only."""

class Simulation(_Readers):
    """One rdem simulation: the interpreter of the rdem command, with its own threads."""

    def __init__(
        self, threads: Optional[int] = None, log: Optional[str] = None, screen: bool = False
    ) -> None:
        """threads: threads of the force pass (default all cores; results do not depend on
        it); log: a log file, as ``-log`` (default none); screen: print the output on
        standard output as the rdem command does."""
    def file(self, path: str) -> None:
        """Runs a script file (as ``rdem -in path``)."""
    def command(self, line: str) -> None:
        """Runs one command line."""
    def commands(self, text: str) -> None:
        """Runs several lines of script."""
    def set_callback(
        self, callback: Optional[Callable[[StepView], Optional[bool]]], every: int = 1
    ) -> None:
        """Calls ``callback(view)`` every ``every`` steps of later runs (None: stop calling).
        Returning False ends the run after that step; an exception ends it and is raised."""
    def view(self, name: str) -> npt.NDArray[np.float64]:
        """A read-only view of rdem's storage of x, v, omega, f, torque, radius, mass or
        density, without a copy; no command runs while a view is alive."""

def cli(args: list[str]) -> int:
    """The rdem command with these arguments; returns its exit status."""
