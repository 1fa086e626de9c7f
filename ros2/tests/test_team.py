"""The bridge's checks without ROS 2 or a team: samples from the team, commands from ROS 2,
arguments and the Zenoh configuration. Every malformed input is counted, none raises."""

import json
import logging

import pytest

from mason_ros2.bridge import parse_args
from mason_ros2.command import Station, parse_command
from mason_ros2.counters import Rejections
from mason_ros2.team import TeamView, parse_scene
from mason_ros2.zenoh_config import config_entries

KEY = "mason/m1/{}/{}"


def status(**kw):
    s = {"state": "FlyToPile", "outcome": "ok", "x": 1.0, "y": 2.0, "z": 5.0, "mode": "comm",
         "brick": None, "claimed_at": 0.0, "grasped": False, "pair": None, "in_zone": False,
         "request": None, "acks": [], "placed": [], "heard": [0.0, -1.0, -1.0], "out": []}
    s.update(kw)
    return s


def message(uav=0, seq=1, t=1.0, kind="heartbeat", incarnation=1, **kw):
    return {"v": 1, "mission": "m1", "uav": uav, "incarnation": incarnation, "seq": seq, "t": t,
            "kind": kind, "status": status(**kw)}


def scene(n=3):
    bricks = [{"brick": i, "label": 10 + i, "type": "red", "centre": [i, 0, 0.1], "size": [0.3, 0.2, 0.2],
               "pending": [0.6, 0.6, 0.6, 0.25], "claimed": [1, 0, 0, 0.4], "placed": [1, 0, 0, 1]}
              for i in range(n)]
    return json.dumps({"v": 1, "wall": "w", "frame": "arena", "ns": "bricks", "bricks": bricks}).encode()


@pytest.fixture
def team():
    view = TeamView("mason", "m1", Rejections(logging.getLogger("test")))
    assert view.set_scene(scene())
    return view


def hear(view, m, key=None):
    key = key or KEY.format(m["uav"], m["kind"])
    return view.hear(key, json.dumps(m).encode())


def test_a_good_message_gives_a_pose_state_and_mission(team):
    h = hear(team, message(uav=1, x=3.0, y=2.0))
    assert h.uav == 1 and (h.pose.x, h.pose.y, h.pose.z) == (3.0, 2.0, 5.0)
    assert h.state and h.mission
    s = team.state_json(1)
    assert s == {"t": 1.0, "uav": 1, "state": "FlyToPile", "outcome": "ok", "brick": None,
                 "mode": "comm", "incarnation": 1, "in_game": True}
    # Heading along the move, as the MCAP logs: north.
    h = hear(team, message(uav=1, seq=2, t=2.0, x=3.0, y=4.0))
    assert abs(h.pose.yaw - 1.5707963) < 1e-6
    assert team.mission_json({})["uavs"] == 3


def test_bricks_are_claimed_then_placed_and_labelled(team):
    hear(team, message(brick=1))
    assert team.brick_statuses() == ["pending", "claimed", "pending"]
    assert team.state_json(0)["brick"] == 11
    h = hear(team, message(seq=2, t=2.0, placed=[1]))
    assert h.wall and team.brick_statuses() == ["pending", "placed", "pending"]
    assert team.mission_json({})["placed"] == 1


def test_a_uav_held_out_by_a_teammate_is_out_of_the_game(team):
    hear(team, message(uav=0))
    hear(team, message(uav=1, out=[{"uav": 0, "incarnation": 1}]))
    assert not team.in_game(0)
    hear(team, message(uav=0, incarnation=2, seq=1, t=3.0))
    assert team.in_game(0)


@pytest.mark.parametrize("payload,key,cause", [
    (b"not json", None, "team/malformed"),
    (b"\xff\xfe", None, "team/malformed"),
    (b"[1, 2]", None, "team/malformed"),
    (b"x" * 70000, None, "team/size"),
    (json.dumps(message(uav=2)).encode(), KEY.format(1, "heartbeat"), "team/key"),
    (json.dumps(message()).encode(), "other/m1/0/heartbeat", "team/key"),
    (json.dumps({**message(), "v": 2}).encode(), None, "team/version"),
    (json.dumps({**message(), "mission": "m2"}).encode(), None, "team/mission"),
    (json.dumps(message(state="Flying")).encode(), None, "team/malformed"),
    (json.dumps(message(x="1")).encode(), None, "team/malformed"),
    (json.dumps(message(uav=7, heard=[0.0, 0.0])).encode(), KEY.format(7, "heartbeat"), "team/range"),
    (json.dumps(message(placed=[5])).encode(), None, "team/range"),
    (json.dumps(message(brick=-1)).encode(), None, "team/range"),
    (json.dumps(message(seq=0)).encode(), None, "team/range"),
    (b"[" * 100000, None, "team/size"),
    (("[" * 5000).encode(), None, "team/malformed"),
])
def test_malformed_samples_are_counted_never_raised(team, payload, key, cause):
    assert team.hear(key or KEY.format(0, "heartbeat"), payload) is None
    assert team.rejections.counts() == {cause: 1}
    assert team.uavs == {}


def test_replays_are_dropped_and_logged_once(team, caplog):
    hear(team, message(seq=5))
    with caplog.at_level(logging.WARNING):
        for _ in range(3):
            assert hear(team, message(seq=5)) is None
    assert team.rejections.counts() == {"team/replay": 3}
    assert len([r for r in caplog.records if "team/replay" in r.getMessage()]) == 1


@pytest.mark.parametrize("payload", [b"{}", b"junk", json.dumps({"v": 1, "bricks": [{"brick": 0}]}).encode()])
def test_a_bad_scene_is_refused(payload):
    assert isinstance(parse_scene(payload), str)


@pytest.mark.parametrize("text,want", [
    ('{"abort": true}', ("abort",)),
    ('{"resume": true}', ("resume",)),
    ('{"land": 2}', ("land", 2)),
    ('{"land": 3}', "command/range"),
    ('{"land": -1}', "command/range"),
    ('{"land": true}', "command/malformed"),
    ('{"land": 1.0}', "command/malformed"),
    ('{"abort": false}', "command/malformed"),
    ('{"abort": true, "land": 1}', "command/malformed"),
    ('{"explode": true}', "command/malformed"),
    ("abort", "command/malformed"),
    ("[]", "command/malformed"),
    ("", "command/malformed"),
    ('{"abort": true}' + " " * 300, "command/size"),
])
def test_commands_are_checked(text, want):
    assert parse_command(text, 3) == want


def test_the_station_numbers_its_commands():
    s = Station("mason", "m1", 2)
    assert s.key == "mason/m1/station-2/command"
    a = json.loads(s.command(("abort",), 12.5))
    b = json.loads(s.command(("land", 1), 13.0))
    assert a == {"v": 1, "mission": "m1", "station": 2, "seq": 1, "t": 12.5, "command": "abort"}
    assert b == {"v": 1, "mission": "m1", "station": 2, "seq": 2, "t": 13.0, "command": "land", "uav": 1}


def test_tls_configures_the_station_certificate(tmp_path):
    for f in ("ca.pem", "cert.pem", "key.pem"):
        (tmp_path / f).write_text("-")
    e = config_entries(["tls/127.0.0.1:7447"], str(tmp_path))
    tls = "transport/link/tls"
    assert json.loads(e[f"{tls}/root_ca_certificate"]) == str(tmp_path / "ca.pem")
    assert json.loads(e[f"{tls}/connect_certificate"]) == str(tmp_path / "cert.pem")
    assert json.loads(e[f"{tls}/connect_private_key"]) == str(tmp_path / "key.pem")
    assert e[f"{tls}/enable_mtls"] == "true"
    # Only TLS links, and no plain listener that an agent could reach without a certificate.
    assert json.loads(e["transport/link/protocols"]) == ["tls"]
    assert json.loads(e["listen/endpoints"]) == []
    # The same over QUIC (the launch's default), and both when both are named.
    assert json.loads(config_entries(["quic/127.0.0.1:7447"], str(tmp_path))["transport/link/protocols"]) == ["quic"]
    both = config_entries(["tls/127.0.0.1:1", "quic/127.0.0.1:2"], str(tmp_path))
    assert json.loads(both["transport/link/protocols"]) == ["quic", "tls"]
    assert "transport/link/protocols" not in config_entries(["tcp/127.0.0.1:1"], None)
    assert "transport/link/tls/root_ca_certificate" not in config_entries(["tcp/127.0.0.1:1"], None)


@pytest.mark.parametrize("argv,words", [
    (["--connect", "127.0.0.1:7447", "--mission", "m"], "not an endpoint"),
    (["--connect", "tcp/127.0.0.1:7447", "--mission", "a/*"], "--mission"),
    (["--connect", "tcp/127.0.0.1:7447", "--mission", "m", "--prefix", "x/**"], "--prefix"),
    (["--connect", "tcp/127.0.0.1:7447", "--mission", "m", "--station", "16"], "0..15"),
    (["--connect", "tcp/127.0.0.1:7447", "--mission", "m", "--tls-dir", "/nonexistent"], "quic/HOST:PORT or tls/HOST:PORT"),
    (["--connect", "quic/127.0.0.1:7447", "--mission", "m", "--tls-dir", "/nonexistent"], "missing"),
    (["--connect", "tls/127.0.0.1:7447", "--mission", "m", "--tls-dir", "/nonexistent"], "missing"),
    (["--mission", "m"], "--connect"),
])
def test_bad_arguments_exit_2_with_one_line(argv, words, capsys):
    with pytest.raises(SystemExit) as e:
        parse_args(argv)
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert words in err
