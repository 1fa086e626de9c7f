"""Reading a bag of Mason's with readers Mason did not write: PyPI's `rosbags` (AnyReader, the
types registered from the installed ROS 2 message packages' own .msg files), Foxglove's
`mcap-ros2-support` (the definitions in the bag) and rclpy's own deserialiser (the C type
support of the ROS 2 wheels)."""

import glob
import json
import os
from pathlib import Path

import rclpy.serialization
from geometry_msgs.msg import PoseStamped
from std_msgs.msg import String
from visualization_msgs.msg import MarkerArray

RCLPY_TYPES = {
    "geometry_msgs/msg/PoseStamped": PoseStamped,
    "std_msgs/msg/String": String,
    "visualization_msgs/msg/MarkerArray": MarkerArray,
}
PACKAGES = ("builtin_interfaces", "std_msgs", "geometry_msgs", "sensor_msgs", "visualization_msgs")


def share_dir() -> Path:
    """The installed ROS 2 message packages' share folder (in this venv)."""
    import sys

    return Path(sys.prefix) / "share"


def installed_typestore():
    """A `rosbags` type store with every type of our topics registered from the installed
    packages' .msg files."""
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    store = get_typestore(Stores.EMPTY)
    types = {}
    for pkg in PACKAGES:
        for f in sorted(glob.glob(str(share_dir() / pkg / "msg" / "*.msg"))):
            name = f"{pkg}/msg/{Path(f).stem}"
            types.update(get_types_from_msg(Path(f).read_text(), name))
    store.register(types)
    return store


PRIMITIVES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16",
              "int32", "uint32", "int64", "uint64", "string", "wstring"}


def fields(msg_text: str, package: str) -> list:
    """A definition's field and constant lines, comments and blank lines left out, and every
    type named in full (``Pose`` in geometry_msgs is ``geometry_msgs/Pose``)."""
    out = []
    for line in msg_text.splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        ty, rest = line.split(None, 1)
        base = ty.split("[", 1)[0].split("<", 1)[0]
        if "/" not in base and base not in PRIMITIVES:
            ty = f"{package}/{ty}"
        out.append(" ".join([ty] + rest.split()))
    return out


def read_rosbags(bag: Path) -> list:
    """Every message as (topic, type, log time ns, decoded message) through rosbags."""
    from rosbags.highlevel import AnyReader

    out = []
    with AnyReader([bag], default_typestore=installed_typestore()) as reader:
        for conn, t, raw in reader.messages():
            out.append((conn.topic, conn.msgtype, t, reader.deserialize(raw, conn.msgtype), raw))
    return out


def read_mcap_ros2(bag: Path) -> list:
    """Every message as (topic, schema name, log time ns, decoded) through mcap-ros2-support."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    with open(next(bag.glob("*.mcap")), "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        return [(c.topic, s.name, m.log_time, d) for s, c, m, d in reader.iter_decoded_messages()]


def rclpy_decode(msgtype: str, raw: bytes):
    return rclpy.serialization.deserialize_message(raw, RCLPY_TYPES[msgtype])


def schemas(bag: Path) -> dict:
    """The bag's schemas: name → (encoding, definition text)."""
    from mcap.reader import make_reader

    with open(next(bag.glob("*.mcap")), "rb") as f:
        summary = make_reader(f).get_summary()
    return {s.name: (s.encoding, s.data.decode()) for s in summary.schemas.values()}


def type_hash(msgtype: str) -> str:
    d = json.loads((share_dir() / (msgtype + ".json")).read_text())
    return next(h["hash_string"] for h in d["type_hashes"] if h["type_name"] == msgtype)


def check_bag(bag: Path, events: list, uavs: int, bricks: int) -> dict:
    """Reads `bag` with all three readers and checks it against the mission's JSON trace
    (`events`, as `simulate --json` or launch's trace.json give them). Returns a summary."""
    assert (bag / "metadata.yaml").is_file()
    # Definitions: each section's fields are those of the installed package's .msg file.
    for name, (encoding, text) in schemas(bag).items():
        assert encoding == "ros2msg", name
        sections = text.split("=" * 80 + "\n")
        own = share_dir() / (name + ".msg")
        pkg = name.split("/")[0]
        assert fields(sections[0], pkg) == fields(own.read_text(), pkg), name
        for sec in sections[1:]:
            head, body = sec.split("\n", 1)
            assert head.startswith("MSG: ")
            pkg, typ = head[5:].split("/")
            real = (share_dir() / pkg / "msg" / f"{typ}.msg").read_text()
            assert fields(body, pkg) == fields(real, pkg), head
    meta = (bag / "metadata.yaml").read_text()
    for t in RCLPY_TYPES:
        if f"type: {t}" in meta:
            assert type_hash(t) in meta, t
    by_rosbags = read_rosbags(bag)
    by_mcap = read_mcap_ros2(bag)
    assert len(by_rosbags) == len(by_mcap) > 0
    topics = {}
    for (topic, msgtype, t, msg, raw), (topic2, name2, t2, msg2) in zip(by_rosbags, by_mcap):
        assert (topic, msgtype, t) == (topic2, name2, t2)
        topics[topic] = topics.get(topic, 0) + 1
        ros = rclpy_decode(msgtype, bytes(raw))
        if msgtype == "geometry_msgs/msg/PoseStamped":
            for m in (msg, msg2, ros):
                assert m.header.frame_id == "arena"
                assert m.header.stamp.sec * 10**9 + m.header.stamp.nanosec == t
            assert (msg.pose.position.x, msg.pose.position.y) == (msg2.pose.position.x, msg2.pose.position.y)
            assert (ros.pose.position.x, ros.pose.orientation.w) == (msg.pose.position.x, msg.pose.orientation.w)
        elif msgtype == "std_msgs/msg/String":
            assert msg.data == msg2.data == ros.data
            json.loads(msg.data)
        else:
            assert len(msg.markers) == len(msg2.markers) == len(ros.markers) == bricks
            assert all(m.type == 1 and m.header.frame_id == "arena" for m in msg.markers)
            assert [m.color.a for m in msg.markers] == [m.color.a for m in msg2.markers]
    assert set(topics) == {f"/mason/uav_{i}/{k}" for i in range(uavs) for k in ("pose", "state")} | {
        "/mason/wall", "/mason/mission"}
    # Poses: at every state event of the trace, a pose of that UAV at that time and place.
    poses = {}
    for topic, msgtype, t, msg, _ in by_rosbags:
        if msgtype == "geometry_msgs/msg/PoseStamped":
            uav = int(topic.split("/")[2][4:])
            poses[(uav, t)] = (msg.pose.position.x, msg.pose.position.y)
    states = [e for e in events if e["kind"] == "state"]
    for e in states:
        x, y = poses[(e["uav"], round(e["t"] * 1e9))]
        assert abs(x - e["x"]) < 1e-9 and abs(y - e["y"]) < 1e-9, e
    # Placements: the bricks opaque on the last wall are those the trace places, and each
    # placement turns its brick opaque at its time.
    placed = [e for e in events if e["kind"] == "place"]
    walls = [(t, msg) for topic, _, t, msg, _ in by_rosbags if topic == "/mason/wall"]
    opaque = {m.id for m in walls[-1][1].markers if m.color.a == 1.0}
    assert opaque == {e["brick"] for e in placed}
    for e in placed:
        t = round(e["t"] * 1e9)
        at = [msg for tw, msg in walls if tw == t]
        assert at and any(m.id == e["brick"] and m.color.a == 1.0 for m in at[-1].markers), e
    missions = [json.loads(msg.data) for topic, _, _, msg, _ in by_rosbags if topic == "/mason/mission"]
    assert missions[-1]["placed"] == len(placed) and missions[-1]["total"] == bricks
    return {"messages": len(by_rosbags), "topics": topics, "placed": len(placed), "poses": len(poses),
            "bytes": sum(os.path.getsize(p) for p in bag.iterdir())}
