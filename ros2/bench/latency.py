"""How far behind the team the bridge runs: a launched team of 3 agents on MBZIRC at
--speed 100, the bridge, and an rclpy subscriber. Prints, over every pose received, the delay
from the agent's send time (mission time 0 at launch's start_at, --speed 100) to the arrival
of the ROS 2 message, its median and p99, per tenth of the mission (a growing backlog shows as
a growing delay), and the bridge's own queue (largest backlog, time a sample waits).

Usage (from the repository root, in the venv of scripts/install-ros2.sh):
    MASON_BIN=target/debug/mason target/ros2env/bin/python ros2/bench/latency.py [RUNS]
"""

import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
os.environ.setdefault("ROS_DOMAIN_ID", str(1 + os.getpid() % 100))

from harness import Subscriber, bridge, free_base_port, latency, launch, stop  # noqa: E402


def ms(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))] * 1e3


def one_run(mason, sub, k):
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        port, mission = free_base_port(), f"bench-{os.getpid()}-{k}"
        for ps in sub.poses.values():
            ps.clear()
        b = bridge(port, mission, d / "bridge.log", d / "stats.json")
        team = launch(mason, d / "out", port, mission, "--insecure")  # the bridge starts first
        _, err = team.communicate(timeout=300)
        time.sleep(1.0)
        stop(b)
        doc = json.loads((d / "out" / "trace.json").read_text())
        stats = json.loads((d / "stats.json").read_text())
        with sub.lock:
            poses = {i: list(p) for i, p in sub.poses.items()}
        delays = latency(poses, doc["start_at"], doc["speed"])
        # Per tenth of the mission, by mission time.
        ts = sorted((t, recv - (doc["start_at"] + t / doc["speed"])) for ps in poses.values() for (t, recv, *_r) in ps)
        end = ts[-1][0]
        tenths = []
        for j in range(10):
            part = [x for t, x in ts if j * end / 10 <= t < (j + 1) * end / 10 or (j == 9 and t == end)]
            tenths.append(round(ms(part, 0.5), 1) if part else None)
        print(json.dumps({
            "run": k, "exit": team.returncode, "placed": doc["summary"]["bricks_placed"], "poses": len(delays),
            "latency_ms": {"median": round(ms(delays, 0.5), 1), "p99": round(ms(delays, 0.99), 1),
                           "max": round(max(delays) * 1e3, 1)},
            "median_ms_by_tenth": tenths, "bridge": {k: stats[k] for k in ("processed", "max_backlog", "queue_delay_s")},
        }))


def main():
    mason = os.environ["MASON_BIN"]
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 1
    sub = Subscriber(3)
    try:
        for k in range(runs):
            one_run(mason, sub, k)
    finally:
        sub.close()


if __name__ == "__main__":
    main()
