"""What the bridge's end-to-end test and its latency benchmark share: a launched team, a
running bridge, and an rclpy subscriber that records what ROS 2 sees."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path


def free_base_port(n: int = 3) -> int:
    """A port P with P..P+n-1 free on 127.0.0.1."""
    for _ in range(50):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            p = s.getsockname()[1]
        if p + n >= 65000:
            continue
        try:
            socks = []
            for i in range(n):
                s = socket.socket()
                socks.append(s)
                s.bind(("127.0.0.1", p + i))
            return p
        except OSError:
            continue
        finally:
            for s in socks:
                s.close()
    raise RuntimeError("no free ports in a row")


def launch(mason: str, out: Path, port: int, mission: str, *extra: str) -> subprocess.Popen:
    """`mason launch builtin:mbzirc` with 3 agents at --speed 100 (extra options after)."""
    args = [mason, "launch", "builtin:mbzirc", "--uavs", "3", "--speed", "100", "--seed", "1",
            "--base-port", str(port), "--mission", mission, "--lead", "2", "--out", str(out), *extra]
    return subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def bridge(port: int, mission: str, log: Path, stats: Path, tls_dir: Path | None = None) -> subprocess.Popen:
    """The installed `mason-ros2-bridge`, connected to agent 0: over mutual TLS in QUIC (the
    launch's default link) with the station files in `tls_dir` (a launch's OUT/station-0), or
    over plain TCP to an `--insecure` team."""
    exe = Path(sys.executable).parent / "mason-ros2-bridge"
    link = f"quic/127.0.0.1:{port}" if tls_dir else f"tcp/127.0.0.1:{port}"
    args = [str(exe), "--connect", link, "--mission", mission, "--stats", str(stats)]
    if tls_dir:
        args += ["--tls-dir", str(tls_dir)]
    return subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=open(log, "w"))


def stop(p: subprocess.Popen, timeout: float = 15.0) -> int:
    """SIGINT, then the exit code (SIGKILL and an error if it does not stop)."""
    p.send_signal(signal.SIGINT)
    try:
        return p.wait(timeout)
    except subprocess.TimeoutExpired:
        p.kill()
        raise AssertionError("did not stop on SIGINT")


class Subscriber:
    """An rclpy node that records the bridge's topics for UAVs 0..uavs-1, and can send
    commands on /mason/command."""

    def __init__(self, uavs: int):
        import rclpy
        from geometry_msgs.msg import PoseStamped
        from rclpy.executors import SingleThreadedExecutor
        from std_msgs.msg import String
        from visualization_msgs.msg import MarkerArray

        from mason_ros2.node import LATEST_QOS, POSE_QOS, STATE_QOS

        if not rclpy.ok():
            rclpy.init()
        self.rclpy = rclpy
        self.node = rclpy.create_node(f"mason_test_{os.getpid()}")
        self.lock = threading.Lock()
        self.poses = {i: [] for i in range(uavs)}
        self.states = {i: [] for i in range(uavs)}
        self.walls = []
        self.missions = []
        for i in range(uavs):
            self.node.create_subscription(PoseStamped, f"/mason/uav_{i}/pose", self._pose(i), POSE_QOS)
            self.node.create_subscription(String, f"/mason/uav_{i}/state", self._state(i), STATE_QOS)
        self.node.create_subscription(MarkerArray, "/mason/wall", self._wall, LATEST_QOS)
        self.node.create_subscription(String, "/mason/mission", self._mission, LATEST_QOS)
        self.commands = self.node.create_publisher(String, "/mason/command", 10)
        self.String = String
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.running = True
        self.thread = threading.Thread(target=self._spin, daemon=True)
        self.thread.start()

    def _spin(self):
        while self.running:
            self.executor.spin_once(timeout_sec=0.05)

    def _pose(self, i):
        def cb(m):
            t = m.header.stamp.sec + m.header.stamp.nanosec * 1e-9
            with self.lock:
                self.poses[i].append((t, time.time(), m.pose.position.x, m.pose.position.y, m.pose.position.z))
        return cb

    def _state(self, i):
        def cb(m):
            with self.lock:
                self.states[i].append(json.loads(m.data))
        return cb

    def _wall(self, m):
        with self.lock:
            self.walls.append([(k.id, k.color.a) for k in m.markers])

    def _mission(self, m):
        with self.lock:
            self.missions.append(json.loads(m.data))

    def wait_for(self, pred, timeout: float) -> bool:
        end = time.time() + timeout
        while time.time() < end:
            with self.lock:
                if pred(self):
                    return True
            time.sleep(0.05)
        return False

    def send(self, text: str, timeout: float = 10.0) -> None:
        """Publishes a command once the bridge subscribes."""
        end = time.time() + timeout
        while self.commands.get_subscription_count() == 0 and time.time() < end:
            time.sleep(0.05)
        m = self.String()
        m.data = text
        self.commands.publish(m)

    def close(self):
        self.running = False
        self.thread.join(2)
        self.executor.shutdown()
        self.node.destroy_node()


def latency(poses: dict, start_at: float, speed: float) -> list:
    """Each pose's delay (s) from its agent's send time (start_at + t / speed, the agents'
    mission clock) to its arrival at the subscriber."""
    return [recv - (start_at + t / speed) for ps in poses.values() for (t, recv, *_rest) in ps]
