"""Commands from ROS 2 (``/mason/command``, ``std_msgs/String`` JSON) checked and turned into
the team's ground-station command (README, "Ground-station commands"):

``{"abort": true}``, ``{"land": I}`` (a UAV of the team) or ``{"resume": true}`` become
``{"v":1,"mission":M,"station":S,"seq":N,"t":T,"command":...}`` on
``PREFIX/MISSION/station-S/command``, with ``seq`` counting from 1 and ``t`` the team's latest
mission time (the agents drop a command more than 120 s behind or 30 s ahead of theirs).
"""

import json

# A command's text is short; anything longer is refused before it is parsed.
MAX_COMMAND = 256


def parse_command(text: str, team_size: int):
    """The order of a command's JSON text, ``("abort",)``, ``("land", i)`` or ``("resume",)``,
    or the cause it is refused for (a string starting with ``command/``)."""
    if len(text) > MAX_COMMAND:
        return "command/size"
    try:
        c = json.loads(text)
    except (ValueError, RecursionError):
        return "command/malformed"
    if not isinstance(c, dict) or len(c) != 1:
        return "command/malformed"
    (name, value), = c.items()
    if name in ("abort", "resume"):
        return (name,) if value is True else "command/malformed"
    if name == "land":
        if not isinstance(value, int) or isinstance(value, bool):
            return "command/malformed"
        if not 0 <= value < team_size:
            return "command/range"
        return ("land", value)
    return "command/malformed"


class Station:
    """A ground station's numbering: each command it sends gets the next ``seq``."""

    def __init__(self, prefix: str, mission: str, station: int):
        self.prefix, self.mission, self.station = prefix, mission, station
        self.seq = 0

    @property
    def key(self) -> str:
        """The key its commands go out on."""
        return f"{self.prefix}/{self.mission}/station-{self.station}/command"

    def command(self, order: tuple, t: float) -> bytes:
        """The wire form of ``order`` sent at mission time ``t``."""
        self.seq += 1
        c = {"v": 1, "mission": self.mission, "station": self.station, "seq": self.seq,
             "t": float(t), "command": order[0]}
        if order[0] == "land":
            c["uav"] = order[1]
        return json.dumps(c).encode()
