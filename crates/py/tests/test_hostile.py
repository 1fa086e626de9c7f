"""Hostile arguments: each raises a Python exception (never a crash, never a hang), and bad
values are mason.InputError (a ValueError) with a message naming what is wrong."""

import numpy as np
import pytest

import mason

WALL = mason.Wall.builtin("thesis-2x5")
GRID = np.zeros((4, 5), dtype=bool)
STARTS = np.array([[0, 0], [4, 3]])
GOALS = np.array([[4, 3], [0, 0]])

CASES = [
    ("negative uavs", lambda: mason.plan_schedule(WALL, uavs=-1), "uavs"),
    ("huge uavs", lambda: mason.plan_schedule(WALL, uavs=10**9), "UAV"),
    ("negative runs", lambda: mason.monte_carlo(WALL, runs=-5), "runs"),
    ("nan budget", lambda: mason.plan_schedule(WALL, objective="reward", budget=float("nan")), "budget"),
    ("inf hazard", lambda: mason.plan_schedule(WALL, objective="expected", budget=100.0, uav_hazard=float("inf")), "hazard"),
    ("faults list", lambda: mason.simulate(WALL, faults=[1, 2, 3]), "faults"),
    ("faults nan", lambda: mason.simulate(WALL, faults={"msg_loss": float("nan")}), "faults"),
    ("faults negative time", lambda: mason.simulate(WALL, faults={"uav_fail": ["0@-1"]}), "0@-1"),
    ("grid 3-D", lambda: mason.crew.solve(np.zeros((2, 2, 2), bool), STARTS, GOALS), "grid"),
    ("grid empty", lambda: mason.crew.solve(np.zeros((0, 5), bool), STARTS, GOALS), "grid"),
    ("grid strings", lambda: mason.crew.solve([["a", "b"]], STARTS, GOALS), ""),
    ("starts object", lambda: mason.crew.solve(GRID, [[object(), 1]], GOALS), ""),
    ("starts negative", lambda: mason.crew.solve(GRID, -STARTS, GOALS), "outside"),
    ("starts huge", lambda: mason.crew.solve(GRID, STARTS + 2**40, GOALS), "outside"),
    ("goal on wall", lambda: mason.crew.solve(np.ones((4, 5), bool), STARTS, GOALS), "obstacle"),
    ("paths ragged", lambda: mason.crew.validate(GRID, STARTS, GOALS, [[[0, 0]], [[1, 2, 3]]]), "paths"),
    ("paths none", lambda: mason.crew.validate(GRID, STARTS, GOALS, None), ""),
    ("agents negative", lambda: mason.crew.load_movingai("x.map", "x.scen", agents=-1), "agents"),
    ("order of other ids", lambda: WALL.svg(order=[999999]), "999999"),
    ("order of negative ids", lambda: WALL.svg(order=[-1]), "-1"),
    ("wall a folder", lambda: mason.Wall.load("/"), "/"),
    ("wall a device", lambda: mason.Wall.load("/dev/zero"), "/dev/zero"),
    ("summarise garbage", lambda: mason.summarise("garbage"), ""),
    ("simulate a string plan", lambda: mason.simulate(WALL, "exact"), "plan_or_schedule"),
]


@pytest.mark.parametrize("name, call, needle", CASES, ids=[c[0] for c in CASES])
def test_hostile_arguments_raise_python_exceptions(name, call, needle):
    with pytest.raises((mason.MasonError, TypeError, ValueError)) as e:
        call()
    assert needle in str(e.value), str(e.value)
