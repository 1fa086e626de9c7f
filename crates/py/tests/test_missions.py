"""Missions and Monte Carlo, cross-checked against `mason simulate --json`."""

import json

import numpy as np
import pytest

import mason


@pytest.fixture(scope="module")
def mbzirc():
    return mason.Wall.builtin("mbzirc")


def test_simulate_equals_the_cli(cli, mbzirc):
    t = mason.simulate(mbzirc, seed=3, faults={"grasp_fail": 0.1})
    theirs = cli("simulate", "builtin:mbzirc", "--seed", "3", "--grasp-fail", "0.1", "--json")
    assert json.loads(t.to_json()) == theirs
    assert t.metrics == theirs["metrics"]
    assert t.events == theirs["events"]
    kinds = {e["kind"] for e in t.events}
    assert {"place", "grasp", "zone_enter", "zone_leave", "state"} <= kinds


def test_simulate_with_windows_and_faults_equals_the_cli(cli, mbzirc):
    faults = {"uav_fail": ["1@300"], "blackout": ["100-400"], "msg_loss": 0.1}
    t = mason.simulate(mbzirc, coord="windows", faults=faults, seed=5)
    theirs = cli(
        "simulate", "builtin:mbzirc", "--coord", "windows", "--uav-fail", "1@300",
        "--blackout", "100-400", "--msg-loss", "0.1", "--seed", "5", "--json",
    )
    assert json.loads(t.to_json()) == theirs
    assert any(e["kind"] == "fail" for e in t.events)


def test_a_plan_and_a_schedule_can_be_flown(cli, mbzirc):
    p = mason.plan_order(mbzirc, planner="greedy")
    t = mason.simulate(mbzirc, p, seed=1)
    theirs = cli("simulate", "builtin:mbzirc", "--planner", "greedy", "--seed", "1", "--json")
    assert t.metrics == theirs["metrics"]
    s = mason.plan_schedule(mbzirc, time_limit=None)
    flown = mason.simulate(mbzirc, s, seed=1)
    assert flown.metrics["bricks_placed"] == 42
    # Without faults every UAV places exactly the bricks the schedule gave it.
    planned = {(int(r["uav"]), int(r["brick"])) for r in s.to_numpy()}
    placed = {(e["uav"], e["brick"]) for e in flown.events if e["kind"] == "place"}
    assert placed <= planned
    assert {b for _, b in placed} == {b for _, b in planned}


def test_monte_carlo_equals_the_cli_and_its_runs_summarise_to_it(cli, mbzirc):
    faults = {"grasp_fail": 0.2, "uav_hazard": 3.0}
    mc = mason.monte_carlo(mbzirc, faults=faults, seed=10, runs=40, per_run=True)
    theirs = cli(
        "simulate", "builtin:mbzirc", "--grasp-fail", "0.2", "--uav-hazard", "3",
        "--seed", "10", "--runs", "40", "--json",
    )
    runs = mc.pop("runs")
    assert mc == theirs
    assert runs["seed"].tolist() == list(range(10, 50))
    assert mason.summarise(runs) == theirs["summary"]
    # Halves summarised together give the whole.
    a = mason.monte_carlo(mbzirc, faults=faults, seed=10, runs=25, per_run=True)["runs"]
    b = mason.monte_carlo(mbzirc, faults=faults, seed=35, runs=15, per_run=True)["runs"]
    assert mason.summarise(np.concatenate([a, b])) == theirs["summary"]


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        ({"coord": "telepathy"}, "coord"),
        ({"faults": {"grasp_fail": 2.0}}, "grasp"),
        ({"faults": {"gravity": 1.0}}, "gravity"),
        ({"faults": {"uav_fail": ["one@two"]}}, "one@two"),
        ({"faults": {"uav_fail": ["7@10"]}}, "7"),
        ({"faults": "not json"}, "faults"),
        ({"uavs": 0}, "uav"),
        ({"plan_or_schedule": 42}, "plan_or_schedule"),
        ({"slot": 0.5, "coord": "windows"}, "slot"),
    ],
)
def test_simulate_refuses_bad_arguments(mbzirc, kwargs, needle):
    with pytest.raises(mason.InputError, match=f"(?i){needle}"):
        mason.simulate(mbzirc, **kwargs)


def test_a_plan_for_another_wall_is_refused(mbzirc):
    p = mason.plan_order(mason.Wall.builtin("thesis-2x5"))
    with pytest.raises(mason.InputError, match="is for wall"):
        mason.simulate(mbzirc, p)
    s = mason.plan_schedule(mbzirc, uavs=2, time_limit=None)
    with pytest.raises(mason.InputError, match="2 UAVs"):
        mason.simulate(mbzirc, s, uavs=3)


def test_monte_carlo_refuses_zero_runs_and_seed_overflow(mbzirc):
    with pytest.raises(mason.InputError, match="runs"):
        mason.monte_carlo(mbzirc, runs=0)
    with pytest.raises(mason.InputError, match="seeds"):
        mason.monte_carlo(mbzirc, seed=2**64 - 1, runs=2)


def test_summarise_refuses_rows_without_the_fields():
    with pytest.raises(mason.InputError, match="complete"):
        mason.summarise({"reward": np.zeros(3)})
