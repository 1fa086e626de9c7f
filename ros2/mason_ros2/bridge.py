"""``mason-ros2-bridge``: joins a running Mason team over Zenoh as a ground station and shows
it to ROS 2; forwards commands sent on ``/mason/command`` to the team.

Usage: ``mason-ros2-bridge --connect EP --mission ID [--prefix P] [--tls-dir DIR]
[--station S] [--stats FILE]``

Exit codes: 0 after SIGINT or SIGTERM (a clean stop), 2 bad arguments. A malformed message
from either side (the team or ROS 2) is counted and logged once per cause; it never ends the
bridge. The bridge may start before the team (it keeps connecting) and outlive it.
"""

import argparse
import json
import logging
import queue
import re
import signal
import statistics
import sys
import threading
import time

from .command import Station, parse_command
from .counters import Rejections
from .team import TeamView
from .zenoh_config import tls_files, zenoh_config

LOG = logging.getLogger("mason-ros2-bridge")
# A key chunk: no Zenoh wildcard or separator characters.
CHUNK = re.compile(r"^[A-Za-z0-9_.\-]+$")
MAX_STATIONS = 16
# How often the bridge asks the team for the wall until one answers (s).
SCENE_RETRY_S = 1.0


def parse_args(argv):
    p = argparse.ArgumentParser(prog="mason-ros2-bridge", description=__doc__.split("\n\n")[0])
    p.add_argument("--connect", action="append", required=True,
                   help="Zenoh endpoint of an agent, e.g. tcp/127.0.0.1:47100; repeatable or comma-separated")
    p.add_argument("--mission", required=True, help="the mission id")
    p.add_argument("--prefix", default="mason", help="key prefix (default mason)")
    p.add_argument("--tls-dir", help="the station's TLS folder: ca.pem, cert.pem, key.pem")
    p.add_argument("--station", type=int, default=0, help="ground station number, 0-15 (default 0)")
    p.add_argument("--stats", help="write the bridge's counts and delays here as JSON when it stops")
    a = p.parse_args(argv)
    endpoints = [e for c in a.connect for e in c.split(",") if e]

    def bad(msg):
        print(f"mason-ros2-bridge: {msg}", file=sys.stderr)
        sys.exit(2)

    if not endpoints:
        bad("--connect: give at least one endpoint, e.g. tcp/127.0.0.1:47100")
    for e in endpoints:
        if not re.match(r"^(tcp|tls|udp|quic)/.+:\d+$", e):
            bad(f"--connect {e}: not an endpoint PROTOCOL/HOST:PORT (tcp, tls, udp, quic)")
        if a.tls_dir is not None and not e.startswith(("quic/", "tls/")):
            bad(f"--connect {e}: with --tls-dir, endpoints are quic/HOST:PORT or tls/HOST:PORT")
    if not CHUNK.match(a.mission):
        bad(f"--mission {a.mission!r}: letters, digits, '_', '-', '.' only")
    if not all(CHUNK.match(c) for c in a.prefix.split("/")):
        bad(f"--prefix {a.prefix!r}: chunks of letters, digits, '_', '-', '.' separated by '/'")
    if not 0 <= a.station < MAX_STATIONS:
        bad(f"--station {a.station}: accepted 0..{MAX_STATIONS - 1}")
    if a.tls_dir is not None:
        files = tls_files(a.tls_dir)
        if isinstance(files, str):
            bad(f"--tls-dir: {files}")
    a.endpoints = endpoints
    return a


def percentile(xs, q):
    if not xs:
        return None
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))]


class Bridge:
    """The running bridge: a Zenoh session, an rclpy node, and the team between them."""

    def __init__(self, a):
        import rclpy
        import zenoh
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.signals import SignalHandlerOptions
        from std_msgs.msg import String

        from . import node as ros

        self.a = a
        self.ros = ros
        self.rejections = Rejections(LOG)
        self.team = TeamView(a.prefix, a.mission, self.rejections)
        self.lock = threading.Lock()
        self.inbox: queue.Queue = queue.Queue()
        self.stop = threading.Event()
        self.spinner: threading.Thread | None = None
        self.station = Station(a.prefix, a.mission, a.station)
        self.delays: list[float] = []
        self.max_backlog = 0
        self.processed = 0
        self.forwarded = 0
        rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
        self.rclpy = rclpy
        self.node = rclpy.create_node("mason_bridge")
        self.pubs = ros.Publishers(self.node)
        self.node.create_subscription(String, ros.COMMAND_TOPIC, self.on_command, 10)
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.session = zenoh.open(zenoh_config(a.endpoints, a.tls_dir))
        base = f"{a.prefix}/{a.mission}"
        self.sub = self.session.declare_subscriber(
            f"{base}/*/*", lambda s: self.inbox.put(("sample", str(s.key_expr), s.payload.to_bytes(), time.monotonic())))
        self.command_pub = self.session.declare_publisher(
            self.station.key, encoding=zenoh.Encoding.APPLICATION_JSON)
        self.scene_key = f"{base}/*/scene"
        self.zenoh = zenoh

    # ---- ROS 2 → team ---------------------------------------------------------------------
    def on_command(self, msg) -> None:
        """A command from ROS 2: checked, then sent to the team as this station's."""
        try:
            with self.lock:
                size, now = self.team.team_size, self.team.time
            order = parse_command(msg.data, size)
            if isinstance(order, str):
                self.rejections.reject(order, f"/mason/command {msg.data[:120]!r}")
                return
            if now is None:
                self.rejections.reject("command/no_team", "no agent heard yet: nothing to command")
                return
            self.command_pub.put(self.station.command(order, now))
            self.forwarded += 1
            LOG.info("forwarded %s to %s at mission time %.1f s", order, self.station.key, now)
        except Exception as e:  # never end the bridge on a command
            self.rejections.reject("command/error", repr(e))

    # ---- team → ROS 2 ---------------------------------------------------------------------
    def ask_scene(self) -> None:
        def on_reply(reply):
            try:
                self.inbox.put(("scene", "", reply.ok.payload.to_bytes(), time.monotonic()))
            except Exception:  # an error reply: asked again later
                pass
        self.session.get(self.scene_key, on_reply)

    def publish_wall(self, t) -> None:
        statuses = self.team.brick_statuses()
        self.pubs.wall.publish(self.ros.wall_msg(self.team.bricks, statuses, t or 0.0))

    def publish_mission(self) -> None:
        body = self.team.mission_json(self.rejections.counts())
        self.pubs.mission.publish(self.ros.string_msg(json.dumps(body)))

    def handle(self, item) -> None:
        kind, key, payload, arrived = item
        with self.lock:
            if kind == "scene":
                if self.team.bricks is None and self.team.set_scene(payload):
                    LOG.info("the wall: %d bricks", len(self.team.bricks))
                    self.publish_wall(self.team.time)
                    self.publish_mission()
                return
            heard = self.team.hear(key, payload)
            if heard is None:
                self.publish_mission()
                return
            pose_pub, state_pub = self.pubs.uav(heard.uav)
            pose_pub.publish(self.ros.pose_msg(heard.pose))
            if heard.state:
                state_pub.publish(self.ros.string_msg(json.dumps(self.team.uavs[heard.uav].state_json)))
            if heard.wall:
                self.publish_wall(heard.pose.t)
            if heard.mission:
                self.publish_mission()
        self.processed += 1
        self.delays.append(time.monotonic() - arrived)

    def run(self) -> None:
        self.spinner = threading.Thread(target=self.spin, daemon=True)
        self.spinner.start()
        last_ask = 0.0
        while not self.stop.is_set():
            if self.team.bricks is None and time.monotonic() - last_ask > SCENE_RETRY_S:
                last_ask = time.monotonic()
                self.ask_scene()
            try:
                item = self.inbox.get(timeout=0.2)
            except queue.Empty:
                continue
            self.max_backlog = max(self.max_backlog, self.inbox.qsize() + 1)
            try:
                self.handle(item)
            except Exception as e:  # a bug or a ROS 2 error: counted, never fatal
                self.rejections.reject("bridge/error", repr(e))

    def spin(self) -> None:
        while not self.stop.is_set() and self.rclpy.ok():
            try:
                self.executor.spin_once(timeout_sec=0.1)
            except Exception as e:
                if self.stop.is_set():
                    return
                self.rejections.reject("bridge/error", repr(e))

    def close(self) -> dict:
        self.stop.set()
        # The ROS 2 spinner must be out of the executor before it is shut down: a spin_once
        # still running while the node is destroyed once ended the process in C++'s
        # std::terminate ("terminate called without an active exception", SIGABRT).
        if self.spinner is not None:
            self.spinner.join(timeout=5.0)
        try:
            self.sub.undeclare()
            self.command_pub.undeclare()
            self.session.close()
        finally:
            self.executor.shutdown(timeout_sec=1.0)
            self.node.destroy_node()
            self.rclpy.try_shutdown()
        d = self.delays
        return {
            "processed": self.processed, "forwarded": self.forwarded,
            "max_backlog": self.max_backlog, "rejected": self.rejections.counts(),
            "queue_delay_s": {"median": statistics.median(d) if d else None, "p99": percentile(d, 0.99),
                              "max": max(d) if d else None},
            "uavs": sorted(self.team.uavs), "placed": len(self.team.placed),
        }


def main(argv=None) -> int:
    logging.basicConfig(level=logging.INFO, format="mason-ros2-bridge: %(message)s")
    a = parse_args(sys.argv[1:] if argv is None else argv)
    bridge = Bridge(a)
    signal.signal(signal.SIGINT, lambda *_: bridge.stop.set())
    signal.signal(signal.SIGTERM, lambda *_: bridge.stop.set())
    LOG.info("joined %s/%s through %s as station %d", a.prefix, a.mission, ",".join(a.endpoints), a.station)
    try:
        bridge.run()
    finally:
        stats = bridge.close()
    if a.stats:
        with open(a.stats, "w") as f:
            json.dump(stats, f, indent=1)
    LOG.info("stopped: %d samples, %d commands forwarded, max backlog %d, rejected %s",
             stats["processed"], stats["forwarded"], stats["max_backlog"], stats["rejected"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
