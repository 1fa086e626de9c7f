"""What a running team says, as the bridge sees it: each agent message checked (the schema of
Mason's README, version 1), each UAV's latest status, the bricks' statuses and the mission
summary. No ROS 2 and no Zenoh here: the node feeds samples in and publishes what changed.

A sample that fails a check is dropped and counted under its cause (``team/<cause>``), and the
first of each cause is logged; nothing a sample holds can raise out of :meth:`TeamView.hear`.
"""

import json
import math
from dataclasses import dataclass, field

KINDS = {"heartbeat", "state", "claim", "zone_request", "zone_enter", "zone_release", "placed"}
STATES = {
    "Check", "TakeOff", "ChooseBrick", "FlyToPile", "Detect", "FlyAbove", "Grasp",
    "FlyToWallWait", "WaitForZone", "EnterAndPlace", "Land", "SafeLand", "Landed", "Down",
}
MODES = {"comm", "windows"}
# The longest sample read (bytes): an agent's is under 5 KB on the MBZIRC wall.
MAX_SAMPLE = 1 << 16
# The largest team and wall the bridge keeps state for.
MAX_UAVS = 64
MAX_BRICKS = 100_000
# A horizontal move shorter than this (m) keeps the heading (as Mason's MCAP logs do).
MIN_MOVE = 1e-6
# The scene layout this bridge reads (mason_report::SCENE_VERSION).
SCENE_VERSION = 1


def _is_int(v) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _is_num(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


@dataclass
class Brick:
    """One brick of the scene: where it goes and its colour by status (r, g, b, a in 0..1)."""

    index: int
    label: int
    centre: tuple
    size: tuple
    colours: dict


def parse_scene(payload: bytes):
    """The bricks of an agent's scene reply (``mason_report::wall_scene_json``), or a reason
    it is refused (a string)."""
    try:
        s = json.loads(payload)
    except (ValueError, UnicodeDecodeError) as e:
        return f"scene: not JSON: {e}"
    if not isinstance(s, dict) or s.get("v") != SCENE_VERSION or not isinstance(s.get("bricks"), list):
        return "scene: not a scene of version 1"
    if len(s["bricks"]) > MAX_BRICKS:
        return "scene: too many bricks"
    bricks = []
    for i, b in enumerate(s["bricks"]):
        ok = (
            isinstance(b, dict) and b.get("brick") == i and _is_int(b.get("label"))
            and all(isinstance(b.get(k), list) and len(b[k]) == 3 and all(_is_num(v) for v in b[k])
                    for k in ("centre", "size"))
            and all(isinstance(b.get(k), list) and len(b[k]) == 4 and all(_is_num(v) for v in b[k])
                    for k in ("pending", "claimed", "placed"))
        )
        if not ok:
            return f"scene: brick {i} malformed"
        colours = {k: tuple(float(v) for v in b[k]) for k in ("pending", "claimed", "placed")}
        bricks.append(Brick(i, b["label"], tuple(b["centre"]), tuple(b["size"]), colours))
    return bricks


def check_message(key: str, m, base: list, bricks: int | None) -> str | None:
    """The cause a message fails (None when it passes): the key, the schema, the ranges."""
    parts = key.split("/")
    if parts[: len(base)] != base or len(parts) != len(base) + 2:
        return "key"
    if not isinstance(m, dict) or not isinstance(m.get("status"), dict):
        return "malformed"
    if m.get("v") != 1:
        return "version"
    if m.get("mission") != base[-1]:
        return "mission"
    uav, s = m.get("uav"), m["status"]
    if not _is_int(uav) or str(uav) != parts[-2] or m.get("kind") != parts[-1]:
        return "key"
    if m.get("kind") not in KINDS or s.get("state") not in STATES or s.get("mode") not in MODES:
        return "malformed"
    if not (_is_int(m.get("incarnation")) and _is_int(m.get("seq")) and _is_num(m.get("t"))):
        return "malformed"
    if not all(_is_num(s.get(f)) for f in ("x", "y", "z")) or not isinstance(s.get("outcome"), str):
        return "malformed"
    placed, out, heard = s.get("placed"), s.get("out"), s.get("heard")
    if not (isinstance(placed, list) and all(_is_int(b) for b in placed)):
        return "malformed"
    if not (isinstance(out, list) and all(isinstance(o, dict) and _is_int(o.get("uav"))
                                          and _is_int(o.get("incarnation")) for o in out)):
        return "malformed"
    if not (isinstance(heard, list) and all(_is_num(h) for h in heard)):
        return "malformed"
    brick = s.get("brick")
    if brick is not None and not _is_int(brick):
        return "malformed"
    n = len(heard)
    if not (0 <= uav < n <= MAX_UAVS) or m["incarnation"] < 1 or m["seq"] < 1:
        return "range"
    if bricks is not None and any(not 0 <= b < bricks for b in placed + ([brick] if brick is not None else [])):
        return "range"
    return None


@dataclass
class Pose:
    """A UAV's pose: mission time (s), position (m, arena frame) and heading (rad from east)."""

    t: float
    x: float
    y: float
    z: float
    yaw: float


@dataclass
class Heard:
    """What one accepted sample changed: the sender's pose, and whether its state, the wall
    and the mission summary changed."""

    uav: int
    pose: Pose
    state: bool
    wall: bool
    mission: bool


@dataclass
class _Uav:
    status: dict
    t: float
    incarnation: int
    seq: int
    yaw: float = 0.0
    last_xy: tuple | None = None
    state_json: dict = field(default_factory=dict)


class TeamView:
    """The team as heard: feed it samples (:meth:`hear`), read its state and mission JSON."""

    def __init__(self, prefix: str, mission: str, rejections):
        self.base = prefix.split("/") + [mission]
        self.mission = mission
        self.rejections = rejections
        self.bricks: list[Brick] | None = None
        self.uavs: dict[int, _Uav] = {}
        self.team_size = 0
        self.placed: set[int] = set()
        self.time: float | None = None
        self._mission_json: dict | None = None
        self._statuses: list[str] | None = None

    # ---- input -------------------------------------------------------------------------
    def set_scene(self, payload: bytes) -> bool:
        """Takes an agent's scene reply; False (counted) if it is refused."""
        got = parse_scene(payload)
        if isinstance(got, str):
            self.rejections.reject("scene/malformed", got)
            return False
        self.bricks = got
        self.placed = {b for b in self.placed if b < len(got)}
        self._statuses = None
        return True

    def hear(self, key: str, payload: bytes) -> Heard | None:
        """One sample from the team: None if it is dropped (counted), else what it changed."""
        if len(payload) > MAX_SAMPLE:
            self.rejections.reject("team/size", f"{key}: {len(payload)} bytes")
            return None
        try:
            m = json.loads(payload)
        except (ValueError, UnicodeDecodeError, RecursionError) as e:
            self.rejections.reject("team/malformed", f"{key}: not JSON: {e}")
            return None
        cause = check_message(key, m, self.base, len(self.bricks) if self.bricks is not None else None)
        if cause is not None:
            self.rejections.reject(f"team/{cause}", f"{key}: {str(m)[:120]}")
            return None
        uav, s = m["uav"], m["status"]
        old = self.uavs.get(uav)
        if old is not None and (m["incarnation"], m["seq"]) <= (old.incarnation, old.seq):
            self.rejections.reject("team/replay", f"{key}: incarnation {m['incarnation']} seq {m['seq']}")
            return None
        u = old or _Uav(status=s, t=m["t"], incarnation=m["incarnation"], seq=m["seq"])
        u.status, u.t, u.incarnation, u.seq = s, m["t"], m["incarnation"], m["seq"]
        self.uavs[uav] = u
        self.team_size = max(self.team_size, len(s["heard"]))
        self.time = m["t"] if self.time is None else max(self.time, m["t"])
        xy = (s["x"], s["y"])
        if u.last_xy is not None and math.hypot(xy[0] - u.last_xy[0], xy[1] - u.last_xy[1]) > MIN_MOVE:
            u.yaw = math.atan2(xy[1] - u.last_xy[1], xy[0] - u.last_xy[0])
        u.last_xy = xy
        pose = Pose(m["t"], s["x"], s["y"], s["z"], u.yaw)
        self.placed.update(s["placed"])
        wall = self._wall_changed()
        state_changed = False
        for i in sorted(self.uavs):
            new = self.state_json(i)
            if new != self.uavs[i].state_json:
                self.uavs[i].state_json = new
                state_changed = state_changed or i == uav
        mission_changed = self._mission_changed()
        return Heard(uav, pose, state_changed, wall, mission_changed)

    # ---- what it says ------------------------------------------------------------------
    def in_game(self, uav: int) -> bool:
        """Whether a UAV is in the game: not down, and no teammate holds its incarnation out."""
        u = self.uavs[uav]
        if u.status["state"] == "Down":
            return False
        held_out = {(o["uav"], o["incarnation"]) for i, v in self.uavs.items() if i != uav
                    for o in v.status["out"]}
        return (uav, u.incarnation) not in held_out

    def _label(self, brick):
        if brick is None or self.bricks is None or brick >= len(self.bricks):
            return brick
        return self.bricks[brick].label

    def state_json(self, uav: int) -> dict:
        """UAV ``uav``'s state message (the keys of the bag's ``/mason/uav_<i>/state``; the
        brick as its label, ``t`` the sender's mission time)."""
        u = self.uavs[uav]
        s = u.status
        return {
            "t": u.t, "uav": uav, "state": s["state"], "outcome": s["outcome"],
            "brick": self._label(s.get("brick")), "mode": s["mode"],
            "incarnation": u.incarnation, "in_game": self.in_game(uav),
        }

    def brick_statuses(self) -> list[str]:
        """Each brick's status (``placed``, ``claimed`` or ``pending``), by wall index."""
        if self.bricks is None:
            return []
        out = ["pending"] * len(self.bricks)
        for i, u in self.uavs.items():
            b = u.status.get("brick")
            if b is not None and b < len(out) and self.in_game(i):
                out[b] = "claimed"
        for b in self.placed:
            out[b] = "placed"
        return out

    def _wall_changed(self) -> bool:
        statuses = self.brick_statuses()
        changed = statuses != self._statuses
        self._statuses = statuses
        return changed and self.bricks is not None

    def mission_json(self, rejected: dict) -> dict:
        """The mission summary: bricks placed of total, the team's mode (``mixed`` when the
        UAVs differ), UAVs in game, the bridge's rejected-message counters."""
        modes = {u.status["mode"] for u in self.uavs.values()}
        return {
            "t": self.time, "placed": len(self.placed),
            "total": len(self.bricks) if self.bricks is not None else None,
            "mode": modes.pop() if len(modes) == 1 else ("mixed" if modes else None),
            "uavs": self.team_size, "in_game": sum(1 for i in self.uavs if self.in_game(i)),
            "rejected": rejected,
        }

    def _mission_changed(self) -> bool:
        now = self.mission_json({})
        now.pop("t")
        changed = now != self._mission_json
        self._mission_json = now
        return changed
