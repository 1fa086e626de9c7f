"""Validators for plans made elsewhere, on what the CLI writes and on plain forms."""

import copy
import json

import pytest

import mason


@pytest.fixture(scope="module")
def mbzirc():
    return mason.Wall.builtin("mbzirc")


def test_validate_order_accepts_plans_dicts_text_and_id_lists(cli, mbzirc):
    plan = mason.plan_order(mbzirc)
    cli_json = cli("plan", "builtin:mbzirc", "--json")
    for given in (plan, cli_json, json.dumps(cli_json), plan.order.tolist(), " ".join(map(str, cli_json["order"]))):
        got = mason.validate_order(mbzirc, given)
        assert got["total_cost"] == pytest.approx(cli_json["total_cost"])
        assert got["steps"] == 42


def test_a_broken_order_names_its_rule(mbzirc):
    order = mason.plan_order(mbzirc).order.tolist()
    swapped = order[:]
    # The first placement above level 1 moved to the very front: before its support.
    k = next(i for i, b in enumerate(order) if b >= 200)
    swapped.insert(0, swapped.pop(k))
    with pytest.raises(mason.ValidationError, match="Unsupported") as e:
        mason.validate_order(mbzirc, swapped)
    assert isinstance(e.value, ValueError)
    with pytest.raises(mason.ValidationError, match="Repeated|WrongLength"):
        mason.validate_order(mbzirc, order[:-1] + [order[0]])
    d = json.loads(mason.plan_order(mbzirc).to_json())
    d["total_cost"] += 10
    with pytest.raises(mason.ValidationError, match="CostMismatch"):
        mason.validate_order(mbzirc, d)


def test_all_lists_every_violation(mbzirc):
    order = mason.plan_order(mbzirc).order.tolist()
    reversed_order = order[::-1]
    with pytest.raises(mason.ValidationError) as e:
        mason.validate_order(mbzirc, reversed_order, all=True)
    assert len(e.value.violations) > 1
    assert all(": " in v for v in e.value.violations)


def test_validate_schedule_on_schedules_json_and_csv(cli, mbzirc):
    s = mason.plan_schedule(mbzirc, time_limit=None)
    got = mason.validate_schedule(mbzirc, s)
    assert got["makespan_s"] == pytest.approx(s.makespan)
    assert got["reward"] == pytest.approx(s.reward)
    assert got["bricks_placed"] == 42
    theirs = cli("plan", "builtin:mbzirc", "--objective", "reward", "--budget", "600", "--json")
    assert mason.validate_schedule(mbzirc, theirs)["reward"] == pytest.approx(theirs["reward"])
    rows = s.to_numpy()
    csv = "uav,brick,start,end\n" + "\n".join(
        f"{int(r['uav'])},{int(r['brick'])},{float(r['start'])!r},{float(r['end'])!r}" for r in rows
    )
    assert mason.validate_schedule(mbzirc, csv, uavs=3)["makespan_s"] == pytest.approx(s.makespan)


def test_a_broken_schedule_names_its_rule(mbzirc):
    s = json.loads(mason.plan_schedule(mbzirc, time_limit=None).to_json())
    early = copy.deepcopy(s)
    # Every placement at time 0: the zone and the precedence cannot both hold.
    for row in early["schedule"]:
        row["end_s"] -= row["start_s"]
        row["start_s"] = 0
    with pytest.raises(mason.ValidationError):
        mason.validate_schedule(mbzirc, early)
    claim = copy.deepcopy(s)
    claim["makespan_s"] -= 50
    with pytest.raises(mason.ValidationError, match="makespan|Makespan|Claim"):
        mason.validate_schedule(mbzirc, claim)
    with pytest.raises(mason.InputError, match="uavs"):
        mason.validate_schedule(mbzirc, s, uavs=0)


def test_check_trace_on_traces_json_and_event_lists(cli, mbzirc):
    t = mason.simulate(mbzirc, seed=2, faults={"grasp_fail": 0.2})
    got = mason.check_trace(mbzirc, t)
    assert got["placed"] == t.metrics["bricks_placed"]
    theirs = cli("simulate", "builtin:mbzirc", "--seed", "2", "--json")
    assert mason.check_trace(mbzirc, theirs)["placed"] == 42
    assert mason.check_trace(mbzirc, theirs["events"], uavs=3)["placed"] == 42


def test_a_broken_trace_names_its_rule(mbzirc):
    events = mason.simulate(mbzirc, seed=2).events
    places = [i for i, e in enumerate(events) if e["kind"] == "place"]
    twice = events + [dict(events[places[0]], t=events[-1]["t"] + 1)]
    with pytest.raises(mason.ValidationError, match="brick"):
        mason.check_trace(mbzirc, twice, uavs=3)
    backwards = [dict(e) for e in events]
    backwards[5]["t"] = -1.0
    with pytest.raises(mason.ValidationError, match="OutOfOrder"):
        mason.check_trace(mbzirc, backwards, uavs=3)


@pytest.mark.parametrize(
    "call, needle",
    [
        (lambda w: mason.validate_order(w, [999]), "999"),
        (lambda w: mason.validate_order(w, "{not json"), "plan"),
        (lambda w: mason.validate_schedule(w, "uav,brick,start\nx,y,z"), "schedule:2"),
        (lambda w: mason.check_trace(w, [{"t": 0, "uav": 0, "kind": "teleport"}]), "trace"),
        (lambda w: mason.check_trace(w, {"events": []}, uavs=-1), "uavs"),
    ],
)
def test_unreadable_artefacts_are_input_errors(mbzirc, call, needle):
    with pytest.raises(mason.InputError) as e:
        call(mbzirc)
    assert needle in str(e.value)
