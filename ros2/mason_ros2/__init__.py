"""Mason's ROS 2 bridge: joins a running UAV team over Zenoh as a ground station and shows it
to ROS 2 (rclpy); forwards ground-station commands sent from ROS 2.

Modules: ``team`` (what the team says, checked: no ROS 2 inside), ``command`` (the commands
ROS 2 sends, checked and turned into the team's wire form), ``zenoh_config`` (the Zenoh
session, with TLS), ``node`` (the rclpy node) and ``bridge`` (the command line).
"""

__all__ = ["team", "command", "zenoh_config", "node", "bridge"]
