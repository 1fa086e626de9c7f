"""Type stubs of mason.crew."""

import os
from typing import Any, Literal, Optional, Union

import numpy as np
import numpy.typing as npt

PathLike = Union[str, "os.PathLike[str]"]

class Solution:
    """A crew plan checked by crew::validate."""

    @property
    def paths(self) -> Optional[npt.NDArray[np.int64]]:
        """(N, T, 2) of (x, y); None when no plan was found."""
    @property
    def goals(self) -> npt.NDArray[np.int64]: ...
    @property
    def sum_of_costs(self) -> Optional[int]: ...
    @property
    def makespan(self) -> Optional[int]: ...
    @property
    def lower_bound(self) -> Optional[int]: ...
    @property
    def status(self) -> Literal["optimal", "feasible", "timeout", "infeasible"]: ...
    @property
    def reason(self) -> Optional[str]: ...
    @property
    def elapsed_s(self) -> float: ...

def load_movingai(
    map_path: PathLike, scen_path: PathLike, agents: Optional[int] = None
) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """(grid, starts, goals) of a MovingAI map and scenario."""

def solve(
    grid: npt.ArrayLike,
    starts: npt.ArrayLike,
    goals: npt.ArrayLike,
    assign: Literal["given", "hungarian", "path", "perm", "joint"] = "given",
    resolve: Literal["lacam", "st", "paper"] = "lacam",
    connectivity: Literal[4, 8] = 4,
    time_limit: Optional[float] = 1.0,
    seed: int = 0,
    paths: Literal["astar", "prm"] = "astar",
) -> Solution:
    """Assigns robots to goals and plans collision-free paths, validated."""

def validate(
    grid: npt.ArrayLike,
    starts: npt.ArrayLike,
    goals: npt.ArrayLike,
    paths: Any,
    connectivity: Literal[4, 8] = 4,
) -> dict[str, int]:
    """Checks a crew plan; raises mason.ValidationError on the first conflict."""
