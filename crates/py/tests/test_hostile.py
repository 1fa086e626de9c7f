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


ZERO_TIMES = """max_time_s = 1000000.0
[uav]
speed = 1e9
check_s = 0.0
takeoff_s = 0.0
land_s = 0.0
detect_s = 0.0
above_s = 0.0
zone_transit_s = 0.0
[faults]
grasp_fail = 0.999
detect_fail = 0.999
"""


def test_a_mission_with_zero_durations_stops_at_its_event_cap(tmp_path):
    # #32: zero durations make events without progress; the mission stops at its event cap
    # with the CLI's message, once or in a batch, instead of filling the memory.
    mission = tmp_path / "zero.toml"
    mission.write_text(ZERO_TIMES)
    wall = mason.Wall.builtin("thesis-2x5")
    with pytest.raises(mason.InputError, match="event cap"):
        mason.simulate(wall, mission=mission)
    with pytest.raises(mason.InputError, match="event cap"):
        mason.monte_carlo(wall, runs=4, mission=mission)
