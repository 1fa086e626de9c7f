"""The rclpy side of the bridge: the publishers (per UAV a pose and a state topic, the wall,
the mission summary), the message builders, and the ``/mason/command`` subscription.

QoS: poses are a stream (reliable, keep last 10, volatile); states keep the last 10 and the
wall and mission summary the latest, transient local, so a late RViz or ``ros2 topic echo``
gets them at once. The bags of ``mason simulate --rosbag`` offer the same profiles.
"""

from geometry_msgs.msg import PoseStamped
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import String
from visualization_msgs.msg import Marker, MarkerArray

FRAME = "arena"
BRICK_NS = "bricks"
COMMAND_TOPIC = "/mason/command"
WALL_TOPIC = "/mason/wall"
MISSION_TOPIC = "/mason/mission"


def qos(depth: int, latched: bool) -> QoSProfile:
    """Reliable, keep last ``depth``; transient local when ``latched``."""
    return QoSProfile(
        history=HistoryPolicy.KEEP_LAST, depth=depth, reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE,
    )


POSE_QOS = qos(10, False)
STATE_QOS = qos(10, True)
LATEST_QOS = qos(1, True)


def stamp_of(msg, t: float) -> None:
    """Sets ``msg.header.stamp`` to mission time ``t`` (s; 0 = mission start, as in the bags)."""
    ns = max(0, round(t * 1e9)) if t == t else 0
    msg.header.stamp.sec = min(ns // 1_000_000_000, 2**31 - 1)
    msg.header.stamp.nanosec = ns % 1_000_000_000


def pose_msg(pose) -> PoseStamped:
    """A UAV's pose in the frame ``arena``, heading as a rotation about z."""
    import math

    m = PoseStamped()
    m.header.frame_id = FRAME
    stamp_of(m, pose.t)
    m.pose.position.x, m.pose.position.y, m.pose.position.z = float(pose.x), float(pose.y), float(pose.z)
    m.pose.orientation.z = math.sin(pose.yaw / 2.0)
    m.pose.orientation.w = math.cos(pose.yaw / 2.0)
    return m


def string_msg(text: str) -> String:
    m = String()
    m.data = text
    return m


def wall_msg(bricks, statuses, t: float) -> MarkerArray:
    """One ``CUBE`` per brick (id: its label), coloured by its status."""
    out = MarkerArray()
    for b, status in zip(bricks, statuses):
        m = Marker()
        m.header.frame_id = FRAME
        stamp_of(m, t)
        m.ns = BRICK_NS
        m.id = int(b.label)
        m.type = Marker.CUBE
        m.action = Marker.ADD
        m.pose.position.x, m.pose.position.y, m.pose.position.z = (float(v) for v in b.centre)
        m.pose.orientation.w = 1.0
        m.scale.x, m.scale.y, m.scale.z = (float(v) for v in b.size)
        r, g, bl, a = b.colours[status]
        m.color.r, m.color.g, m.color.b, m.color.a = r, g, bl, a
        out.markers.append(m)
    return out


class Publishers:
    """The bridge's publishers; a UAV's are made when it is first heard."""

    def __init__(self, node):
        self.node = node
        self.pose: dict[int, object] = {}
        self.state: dict[int, object] = {}
        self.wall = node.create_publisher(MarkerArray, WALL_TOPIC, LATEST_QOS)
        self.mission = node.create_publisher(String, MISSION_TOPIC, LATEST_QOS)

    def uav(self, i: int):
        """UAV ``i``'s pose and state publishers."""
        if i not in self.pose:
            self.pose[i] = self.node.create_publisher(PoseStamped, f"/mason/uav_{i}/pose", POSE_QOS)
            self.state[i] = self.node.create_publisher(String, f"/mason/uav_{i}/state", STATE_QOS)
        return self.pose[i], self.state[i]
