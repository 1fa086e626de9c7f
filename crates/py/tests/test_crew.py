"""Crews and MAPF from numpy arrays, cross-checked against `mason crew --json`."""

import numpy as np
import pytest

import mason
from conftest import shared


@pytest.fixture(scope="module")
def room(data):
    return mason.crew.load_movingai(data / "crew-room.map", data / "crew-room.scen")


def test_load_movingai_gives_numpy_arrays(room, data):
    grid, starts, goals = room
    assert grid.dtype == np.bool_ and grid.ndim == 2
    assert starts.shape == goals.shape and starts.shape[1] == 2
    h, w = grid.shape
    assert (w, h) == (10, 6)
    assert not grid[starts[:, 1], starts[:, 0]].any()
    two = mason.crew.load_movingai(data / "crew-room.map", data / "crew-room.scen", agents=2)
    assert two[1].shape == (2, 2)


@pytest.mark.parametrize("connectivity", [4, 8])
def test_solve_equals_the_cli_and_passes_the_validator(cli, room, data, connectivity):
    grid, starts, goals = room
    sol = mason.crew.solve(grid, starts, goals, resolve="st", connectivity=connectivity)
    theirs = cli(
        "crew", data / "crew-room.map", "--scen", data / "crew-room.scen",
        "--resolve", "st", "--connectivity", connectivity, "--json",
    )
    assert sol.status == theirs["status"]
    assert sol.sum_of_costs == theirs["sum_of_costs"]
    assert sol.makespan == theirs["makespan"]
    assert sol.lower_bound == theirs["lower_bound_sum_of_costs"]
    paths = sol.paths
    assert paths.dtype == np.int64 and paths.shape[0] == len(starts) and paths.shape[2] == 2
    for i, agent in enumerate(theirs["agents"]):
        mine = paths[i].tolist()
        assert mine[: len(agent["path"])] == agent["path"]
        assert all(c == agent["goal"] for c in mine[len(agent["path"]) :])
    checked = mason.crew.validate(grid, starts, goals, paths, connectivity)
    assert checked == {"sum_of_costs": sol.sum_of_costs, "makespan": sol.makespan}


def test_lacam_and_joint_plans_are_valid(room):
    grid, starts, goals = room
    for kwargs in ({"resolve": "lacam"}, {"assign": "joint"}, {"assign": "hungarian"}):
        sol = mason.crew.solve(grid, starts, goals, time_limit=0.5, **kwargs)
        assert sol.status in ("optimal", "feasible"), (kwargs, sol.reason)
        assert sol.sum_of_costs >= sol.lower_bound
        mason.crew.validate(grid, starts, sol.goals, sol.paths, 4)


def test_a_movingai_benchmark_map_with_many_robots():
    grid, starts, goals = mason.crew.load_movingai(
        shared("mapf", "maps", "random-32-32-10.map"),
        shared("mapf", "scen", "random-32-32-10-random-1.scen"),
        agents=100,
    )
    sol = mason.crew.solve(grid, starts, goals, time_limit=1.0)
    assert sol.status in ("optimal", "feasible")
    assert sol.paths.shape[:1] == (100,)
    mason.crew.validate(grid, starts, goals, sol.paths, 4)


def test_validate_names_the_first_conflict(room):
    grid, starts, goals = room
    sol = mason.crew.solve(grid, starts, goals, resolve="st")
    paths = sol.paths.copy()
    # Robot 1 stands where robot 0 is at step 1: a vertex conflict (or a jump).
    paths[1, 1] = paths[0, 1]
    with pytest.raises(mason.ValidationError) as e:
        mason.crew.validate(grid, starts, goals, paths, 4)
    assert "robot" in str(e.value)
    bad_start = sol.paths.copy()
    bad_start[0, 0] = bad_start[1, 0]
    with pytest.raises(mason.ValidationError):
        mason.crew.validate(grid, starts, goals, bad_start, 4)
    with pytest.raises(mason.ValidationError, match="paths"):
        mason.crew.validate(grid, starts, goals, sol.paths[:-1], 4)


@pytest.mark.parametrize(
    "change, needle",
    [
        (lambda g, s, t: (g[0], s, t), "grid"),
        (lambda g, s, t: (g, s.astype(float), t), "integers"),
        (lambda g, s, t: (g, s + 100, t), "outside"),
        (lambda g, s, t: (g, s[:, :1], t), "(N, 2)"),
        (lambda g, s, t: (g, s[:0], t[:0]), "no robots"),
        (lambda g, s, t: (g, np.vstack([s, s[:1]]), np.vstack([t, t[:1]])), "robot"),
    ],
)
def test_solve_refuses_bad_arrays(room, change, needle):
    grid, starts, goals = change(*room)
    with pytest.raises(mason.InputError) as e:
        mason.crew.solve(grid, starts, goals)
    assert needle in str(e.value)


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        ({"assign": "lottery"}, "assign"),
        ({"resolve": "magic"}, "resolve"),
        ({"connectivity": 6}, "connectivity"),
        ({"paths": "teleport"}, "paths"),
        ({"time_limit": 0.0}, "time_limit"),
    ],
)
def test_solve_refuses_bad_options(room, kwargs, needle):
    with pytest.raises(mason.InputError, match=needle):
        mason.crew.solve(*room, **kwargs)


def test_load_movingai_names_the_bad_file(data):
    with pytest.raises(mason.InputError, match="crew-bad"):
        mason.crew.load_movingai(data / "crew-bad.map", data / "crew-room.scen")
