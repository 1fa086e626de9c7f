"""The bridge end to end: a launched team (3 agents over Zenoh, --speed 100), the bridge, and
an rclpy subscriber in this test. Also: commands from ROS 2, malformed messages from either
side, a bridge started before its team, and a team that ends while the bridge runs."""

import json
import time

import pytest

from bags import check_bag
from harness import Subscriber, bridge, free_base_port, latency, launch, stop

UAVS, BRICKS = 3, 42


@pytest.fixture
def sub():
    s = Subscriber(UAVS)
    yield s
    s.close()


def test_a_bridge_started_before_its_team_shows_the_whole_mission(mason_zenoh, tmp_path, sub):
    port, mission = free_base_port(), f"ros-{int(time.time())}"
    b = bridge(port, mission, tmp_path / "bridge.log", tmp_path / "stats.json")
    time.sleep(2.0)
    assert b.poll() is None, (tmp_path / "bridge.log").read_text()
    # The launch makes its mission authority when it starts, after this bridge: a trusted bench
    # (--insecure). The TLS team is the abort test's below.
    team = launch(mason_zenoh, tmp_path / "out", port, mission, "--rosbag", str(tmp_path / "bag"), "--insecure")
    out, err = team.communicate(timeout=180)
    assert team.returncode == 0, err
    assert sub.wait_for(lambda s: s.missions and s.missions[-1]["placed"] == BRICKS, 10), sub.missions[-3:]
    m = sub.missions[-1]
    assert (m["total"], m["uavs"]) == (BRICKS, UAVS), m
    assert all(len(sub.poses[i]) > 50 for i in range(UAVS)), {i: len(p) for i, p in sub.poses.items()}
    assert all(p[0][4] >= 0.0 and p[-1][4] == 0.0 for p in sub.poses.values())  # landed at the end
    assert sub.walls and all(len(w) == BRICKS for w in sub.walls)
    assert sorted(a for _, a in sub.walls[-1]) == [1.0] * BRICKS
    assert all(sub.states[i][-1]["state"] == "Landed" for i in range(UAVS)), [s[-1] for s in sub.states.values()]
    # The team has ended; the bridge runs on, and stops cleanly on SIGINT.
    time.sleep(1.5)
    assert b.poll() is None, (tmp_path / "bridge.log").read_text()
    assert stop(b) == 0, (tmp_path / "bridge.log").read_text()
    stats = json.loads((tmp_path / "stats.json").read_text())
    assert stats["uavs"] == [0, 1, 2] and stats["placed"] == BRICKS, stats
    assert not any(k.startswith("bridge/") for k in stats["rejected"]), stats
    doc = json.loads((tmp_path / "out" / "trace.json").read_text())
    d = sorted(latency(sub.poses, doc["start_at"], doc["speed"]))
    print(f"poses {len(d)}, latency median {d[len(d) // 2] * 1e3:.1f} ms, p99 {d[int(0.99 * len(d))] * 1e3:.1f} ms, "
          f"max backlog {stats['max_backlog']}")
    # The launch's bag: the merged trace, read back by rosbags, mcap-ros2-support and rclpy.
    print(check_bag(tmp_path / "bag", doc["events"], UAVS, BRICKS))


def test_an_abort_from_ros_lands_every_agent_and_junk_is_counted(mason_zenoh, tmp_path, sub):
    import zenoh

    port, mission = free_base_port(), f"abort-{int(time.time())}"
    # Junk on the team's keys needs a plain link: an --insecure team.
    team = launch(mason_zenoh, tmp_path / "out", port, mission, "--insecure")
    time.sleep(1.0)
    b = bridge(port, mission, tmp_path / "bridge.log", tmp_path / "stats.json")
    # Junk from ROS 2 before and after the team is heard: counted, never forwarded.
    for junk in ("nonsense", '{"land": 9}', '{"abort": false}', '{"abort": true, "resume": true}'):
        sub.send(junk)
    # Junk on the team's keys: counted by the bridge (and by the agents), never fatal.
    conf = zenoh.Config()
    conf.insert_json5("mode", '"peer"')
    conf.insert_json5("scouting/multicast/enabled", "false")
    conf.insert_json5("connect/endpoints", json.dumps([f"tcp/127.0.0.1:{port}"]))
    with zenoh.open(conf) as z:
        assert sub.wait_for(lambda s: any(s.poses.values()), 30), (tmp_path / "bridge.log").read_text()
        for payload in (b"junk", b"{}", b"[" * 100, json.dumps({"v": 1, "mission": mission}).encode()):
            z.put(f"mason/{mission}/0/heartbeat", payload)
        assert sub.wait_for(lambda s: s.missions and s.missions[-1]["placed"] >= 1, 60)
        sub.send('{"abort": true}')
        out, err = team.communicate(timeout=180)
    assert sub.wait_for(lambda s: s.missions and s.missions[-1]["rejected"].get("team/malformed", 0) >= 3, 10), \
        sub.missions[-1]
    assert (tmp_path / "out" / "trace.json").is_file(), err
    rejected = sub.missions[-1]["rejected"]
    assert rejected.get("command/malformed") == 3 and rejected.get("command/range") == 1, rejected
    doc = json.loads((tmp_path / "out" / "trace.json").read_text())
    assert team.returncode == 1, err  # aborted: the wall is unfinished
    assert doc["summary"]["check_trace"] == "passed"
    for u in range(UAVS):
        landed = [e for e in doc["events"] if e["uav"] == u and e["kind"] == "state"
                  and e["state"] in ("Land", "Landed") and e["outcome"] == "aborted"]
        assert landed, f"UAV {u} did not land on the abort"
    assert doc["summary"]["bricks_placed"] < BRICKS
    assert stop(b) == 0, (tmp_path / "bridge.log").read_text()
    stats = json.loads((tmp_path / "stats.json").read_text())
    assert stats["forwarded"] == 1, stats


def test_over_mutual_tls_the_bridge_sees_the_team_and_its_abort_lands_every_agent(mason_zenoh, tmp_path, sub):
    # The default team: a mission authority made by the launch; the bridge joins with the
    # station's certificate, sees the team and forwards an authenticated abort.
    port, mission = free_base_port(), f"tls-{int(time.time())}"
    team = launch(mason_zenoh, tmp_path / "out", port, mission)
    station = tmp_path / "out" / "station-0"
    deadline = time.monotonic() + 30
    while not (station / "key.pem").is_file() and time.monotonic() < deadline:
        time.sleep(0.1)
    assert (station / "key.pem").is_file(), "the launch made no station keys"
    b = bridge(port, mission, tmp_path / "bridge.log", tmp_path / "stats.json", tls_dir=station)
    assert sub.wait_for(lambda s: all(s.poses[i] for i in range(UAVS)), 60), (tmp_path / "bridge.log").read_text()
    assert sub.wait_for(lambda s: s.walls and len(s.walls[-1]) == BRICKS, 30)
    assert sub.wait_for(lambda s: s.missions and s.missions[-1]["placed"] >= 1, 60)
    sub.send('{"abort": true}')
    out, err = team.communicate(timeout=180)
    doc = json.loads((tmp_path / "out" / "trace.json").read_text())
    assert doc["security"] == "mutual-tls", doc.get("security")
    assert doc["summary"]["check_trace"] == "passed"
    for u in range(UAVS):
        assert any(e["uav"] == u and e["kind"] == "state" and e["outcome"] == "aborted" for e in doc["events"]), \
            f"UAV {u} did not land on the abort"
    assert stop(b) == 0, (tmp_path / "bridge.log").read_text()
    assert json.loads((tmp_path / "stats.json").read_text())["forwarded"] == 1
