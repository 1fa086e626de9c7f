"""Type stubs of Mason's Python API (the fixed names of the package's README)."""

import os
from typing import Any, Callable, Literal, Optional, Union

import numpy as np
import numpy.typing as npt

from . import crew as crew

__version__: str

PathLike = Union[str, "os.PathLike[str]"]
Status = Literal["optimal", "feasible", "timeout", "infeasible"]

class MasonError(Exception):
    """Base class of every error Mason raises."""

class InputError(MasonError, ValueError):
    """Bad input or a bad argument (the CLI's exit code 2), with the CLI's one-line message."""

class NoSolutionError(MasonError):
    """No solution within the budget, or none exists (the CLI's exit code 1)."""

class ValidationError(MasonError, ValueError):
    """A validator found a broken rule; `violations` lists "Rule: message" lines."""

    violations: list[str]

def builtin_walls() -> list[str]:
    """The names of the built-in walls."""

class Wall:
    """A wall design: bricks, supports (the precedence DAG) and neighbours."""

    @staticmethod
    def load(
        path: PathLike,
        format: Literal["auto", "text", "mbzirc", "png", "cmcp"] = "auto",
        cmcp_sizes: Literal["yaml", "swapped"] = "yaml",
        strict: bool = False,
    ) -> Wall:
        """Reads a layer-text, MBZIRC, PNG or CMCP wall design."""
    @staticmethod
    def builtin(name: str) -> Wall:
        """A built-in wall (see builtin_walls())."""
    def __len__(self) -> int: ...
    @property
    def name(self) -> str: ...
    @property
    def levels(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def bricks(self) -> list[dict[str, Any]]:
        """Dicts with id, type, level, segment, x, y, footprint, supports, neighbours."""
    def to_json(self) -> str:
        """The JSON of `mason wall show --json`."""
    def svg(self, order: Optional[list[int]] = None) -> str:
        """The wall as SVG, numbered in `order` if given."""

class Plan:
    """A build order checked by the order validator."""

    @property
    def order(self) -> npt.NDArray[np.int64]:
        """Brick ids, first placed first."""
    @property
    def total_cost(self) -> float: ...
    @property
    def status(self) -> Status: ...
    @property
    def planner(self) -> str: ...
    @property
    def steps(self) -> list[dict[str, Any]]:
        """Dicts with id, placed_neighbours and cost."""
    def to_json(self) -> str:
        """The JSON of `mason plan --json`."""
    def __len__(self) -> int: ...

class Schedule:
    """A team schedule checked by the schedule validator and against its bound."""

    @property
    def makespan(self) -> float: ...
    @property
    def reward(self) -> float: ...
    @property
    def expected_reward(self) -> Optional[float]: ...
    @property
    def bound(self) -> float: ...
    @property
    def gap(self) -> float: ...
    @property
    def status(self) -> Status: ...
    @property
    def objective(self) -> Literal["makespan", "reward", "expected"]: ...
    @property
    def uavs(self) -> int: ...
    def to_numpy(self) -> np.ndarray:
        """A structured array with fields uav, brick, start and end."""
    def to_json(self) -> str:
        """The JSON of `mason plan --objective ... --json`."""
    def __len__(self) -> int: ...

class Trace:
    """One flown mission."""

    @property
    def metrics(self) -> dict[str, Any]: ...
    @property
    def events(self) -> list[dict[str, Any]]: ...
    def to_json(self) -> str:
        """The JSON of `mason simulate --json`."""

def plan_order(
    wall: Wall,
    planner: str = "exact",
    model: Optional[PathLike] = None,
    time_limit: Optional[float] = None,
) -> Plan:
    """Plans a build order (exact, greedy, brute or improved:N,K) and validates it."""

def plan_schedule(
    wall: Wall,
    objective: Literal["makespan", "reward", "expected"] = "makespan",
    uavs: int = 3,
    model: str = "thesis",
    budget: Optional[float] = None,
    uav_hazard: Optional[float] = None,
    time_limit: Optional[float] = 1.0,
    seed: int = 0,
    progress: Optional[Callable[[dict[str, float]], Any]] = None,
    metric: Optional[Literal["xy", "xyz"]] = None,
) -> Schedule:
    """Plans a team schedule and validates it; progress gets the best so far now and then."""

def simulate(
    wall: Wall,
    plan_or_schedule: Union[Plan, Schedule, None] = None,
    uavs: int = 3,
    coord: Literal["comm", "windows", "auto"] = "comm",
    faults: Optional[dict[str, Any]] = None,
    seed: int = 0,
    model: Optional[PathLike] = None,
    mission: Optional[PathLike] = None,
    slot: Optional[float] = None,
) -> Trace:
    """Flies one mission and checks its trace."""

def monte_carlo(
    wall: Wall,
    plan_or_schedule: Union[Plan, Schedule, None] = None,
    uavs: int = 3,
    coord: Literal["comm", "windows", "auto"] = "comm",
    faults: Optional[dict[str, Any]] = None,
    seed: int = 0,
    runs: int = 100,
    model: Optional[PathLike] = None,
    mission: Optional[PathLike] = None,
    slot: Optional[float] = None,
    per_run: bool = False,
) -> dict[str, Any]:
    """Flies seeds seed..seed+runs-1 and returns the summary of `simulate --runs N --json`."""

def summarise(runs: np.ndarray) -> dict[str, Any]:
    """The summary of per-run rows from monte_carlo(..., per_run=True)."""

def validate_order(
    wall: Wall,
    plan: Union[Plan, dict[str, Any], str, list[int]],
    model: Optional[PathLike] = None,
    all: bool = False,
) -> dict[str, Any]:
    """Checks a build order (a Plan, plan --json as dict or text, or brick ids); raises ValidationError."""

def validate_schedule(
    wall: Wall,
    schedule: Union[Schedule, dict[str, Any], str],
    model: Optional[str] = None,
    uavs: Optional[int] = None,
    budget: Optional[float] = None,
    all: bool = False,
    metric: Optional[Literal["xy", "xyz"]] = None,
) -> dict[str, Any]:
    """Checks a team schedule (a Schedule, plan --objective --json, or uav,brick,start[,end] CSV text)."""

def check_trace(
    wall: Wall,
    trace: Union[Trace, dict[str, Any], str, list[dict[str, Any]]],
    uavs: Optional[int] = None,
    all: bool = False,
) -> dict[str, int]:
    """Checks a mission trace (a Trace, simulate --json, launch's trace.json, or a list of events)."""
