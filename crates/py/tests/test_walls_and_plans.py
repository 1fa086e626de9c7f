"""Walls, build orders and team schedules, cross-checked against the CLI's JSON."""

import json

import numpy as np
import pytest

import mason
from conftest import shared, without_stats


def test_builtin_walls_have_their_bricks_and_the_clis_json(cli):
    assert "mbzirc" in mason.builtin_walls()
    w = mason.Wall.builtin("mbzirc")
    assert len(w) == 42
    bricks = w.bricks
    assert len(bricks) == 42
    first = bricks[0]
    for key in ("id", "type", "level", "x", "y", "footprint", "supports", "neighbours"):
        assert key in first
    assert first["level"] == 1 and first["id"] == 101
    assert json.loads(w.to_json()) == cli("wall", "show", "builtin:mbzirc", "--json")
    svg = w.svg()
    assert svg.startswith("<svg") and "101" in svg


def test_walls_load_from_text_png_and_cmcp(data):
    text = mason.Wall.load(data / "wall-ok.txt")
    assert len(text) > 0
    png = mason.Wall.load(data / "wall-imagemagick.png")
    assert len(png) > 0 and png.levels >= 1



def test_cmcp_walls_load():
    marco = shared("walls-cmcp", "config", "Marco_1.txt")
    cmcp = mason.Wall.load(marco)
    assert len(cmcp) > 0
    assert len(mason.Wall.load(marco, format="cmcp", cmcp_sizes="swapped")) == len(cmcp)


def test_the_cmcp_benchmark_walls_load_and_plan():
    w = mason.Wall.load(shared("walls-cmcp", "config", "wall_256_multi.txt"))
    assert len(w) == 256
    s = mason.plan_schedule(w, objective="reward", budget=2500, model="cmcp", time_limit=0.5)
    assert s.reward <= s.bound + 1e-9
    assert s.status in ("optimal", "feasible", "timeout")


@pytest.mark.parametrize(
    "call, needle",
    [
        (lambda d: mason.Wall.load(d / "wall-bad-token.txt"), "wall-bad-token.txt"),
        (lambda d: mason.Wall.load(d / "no-such-file.txt"), "no-such-file.txt"),
        (lambda d: mason.Wall.load(d / "not-a-png.png"), "not-a-png.png"),
        (lambda d: mason.Wall.load(d / "cmcp-bad-fields.txt", format="cmcp"), "cmcp-bad-fields.txt"),
        (lambda d: mason.Wall.load(d / "wall-ok.txt", format="jpeg"), "format"),
        (lambda d: mason.Wall.load(d / "wall-ok.txt", cmcp_sizes="big"), "cmcp_sizes"),
        (lambda d: mason.Wall.builtin("cathedral"), "no such built-in wall"),
    ],
)
def test_bad_walls_raise_input_errors_naming_the_cause(data, call, needle):
    with pytest.raises(mason.InputError) as e:
        call(data)
    assert needle in str(e.value)
    assert isinstance(e.value, ValueError) and isinstance(e.value, mason.MasonError)


def test_a_bad_line_is_named(data):
    with pytest.raises(mason.InputError, match=r"wall-bad-token.txt:\d+"):
        mason.Wall.load(data / "wall-bad-token.txt")


@pytest.mark.parametrize("planner", ["exact", "greedy", "improved:1,4"])
def test_plan_order_equals_the_cli(cli, planner):
    w = mason.Wall.builtin("thesis-2x5")
    p = mason.plan_order(w, planner=planner)
    mine = json.loads(p.to_json())
    theirs = cli("plan", "builtin:thesis-2x5", "--planner", planner, "--json")
    assert without_stats(mine) == without_stats(theirs)
    assert isinstance(p.order, np.ndarray) and p.order.dtype == np.int64
    assert p.order.tolist() == theirs["order"]
    assert p.total_cost == pytest.approx(theirs["total_cost"])
    assert p.status == theirs["status"]
    assert p.steps == theirs["steps"]
    assert len(p) == len(w)


def test_plan_order_with_a_model_file(data, cli):
    w = mason.Wall.builtin("thesis-2x5")
    p = mason.plan_order(w, model=data / "model-ok.toml")
    theirs = cli("plan", "builtin:thesis-2x5", "--model", data / "model-ok.toml", "--json")
    assert p.total_cost == pytest.approx(theirs["total_cost"])
    with pytest.raises(mason.InputError, match="model-bad.toml"):
        mason.plan_order(w, model=data / "model-bad.toml")


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        ({"planner": "quantum"}, "planner"),
        ({"time_limit": -1.0}, "time_limit"),
        ({"time_limit": float("nan")}, "time_limit"),
        ({"time_limit": 1e300}, "time_limit"),
    ],
)
def test_plan_order_refuses_bad_arguments(kwargs, needle):
    with pytest.raises(mason.InputError, match=needle):
        mason.plan_order(mason.Wall.builtin("thesis-2x5"), **kwargs)


@pytest.mark.parametrize(
    "objective, extra",
    [
        ("makespan", []),
        ("reward", ["--budget", "600"]),
        ("expected", ["--budget", "600", "--uav-hazard", "2"]),
    ],
)
def test_plan_schedule_equals_the_cli_without_a_time_limit(cli, objective, extra):
    w = mason.Wall.builtin("mbzirc")
    kwargs = {}
    if "--budget" in extra:
        kwargs["budget"] = 600.0
    if "--uav-hazard" in extra:
        kwargs["uav_hazard"] = 2.0
    s = mason.plan_schedule(w, objective=objective, time_limit=None, seed=4, **kwargs)
    theirs = cli("plan", "builtin:mbzirc", "--objective", objective, "--seed", "4", "--json", *extra)
    mine = json.loads(s.to_json())
    assert without_stats(mine) == without_stats(theirs)
    assert s.makespan == pytest.approx(theirs["makespan_s"])
    assert s.reward == pytest.approx(theirs["reward"])
    assert s.bound == pytest.approx(theirs["bound"])
    assert s.gap == pytest.approx(theirs["gap"])
    assert s.status == theirs["status"]
    rows = s.to_numpy()
    assert rows.dtype.names == ("uav", "brick", "start", "end")
    assert len(rows) == len(theirs["schedule"])
    for row, want in zip(rows, theirs["schedule"]):
        assert (int(row["uav"]), int(row["brick"])) == (want["uav"], want["brick"])
        assert row["start"] == pytest.approx(want["start_s"])
        assert row["end"] == pytest.approx(want["end_s"])


def test_the_same_seed_gives_the_same_schedule():
    w = mason.Wall.builtin("levels5-width10")
    a = mason.plan_schedule(w, time_limit=None, seed=7)
    b = mason.plan_schedule(w, time_limit=None, seed=7)
    assert np.array_equal(a.to_numpy(), b.to_numpy())


def test_progress_reports_better_and_better_results():
    seen = []
    w = mason.Wall.builtin("mbzirc")
    s = mason.plan_schedule(w, time_limit=0.3, progress=seen.append)
    assert seen, "progress was never called"
    values = [d["value"] for d in seen]
    assert values == sorted(values, reverse=True), values
    assert values[-1] == pytest.approx(s.makespan)
    assert all(d["bound"] == pytest.approx(s.bound) for d in seen)


def test_an_exception_in_progress_stops_the_search_and_is_raised():
    def boom(_):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        mason.plan_schedule(mason.Wall.builtin("mbzirc"), time_limit=5.0, progress=boom)


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        ({"objective": "speed"}, "objective"),
        ({"objective": "reward"}, "budget"),
        ({"objective": "expected", "budget": 600.0}, "uav-hazard"),
        ({"uav_hazard": 1.0}, "uav-hazard"),
        ({"uavs": 0}, "UAV"),
        ({"model": "no-such-model"}, "no-such-model"),
    ],
)
def test_plan_schedule_refuses_bad_arguments(kwargs, needle):
    with pytest.raises(mason.InputError, match=needle):
        mason.plan_schedule(mason.Wall.builtin("mbzirc"), **kwargs)
