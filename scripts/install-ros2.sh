#!/usr/bin/env bash
# Installs ROS 2's Python client library from PyPI (ros-rclpy 9.1.2, ROS 2 Kilted, with Fast
# DDS; the message packages std_msgs, geometry_msgs and visualization_msgs 5.5.1), the bag
# readers Mason's tests check its bags with (rosbags 0.11.9, mcap-ros2-support 0.6.0),
# eclipse-zenoh 1.10.2 (the Rust crate's version: the wire protocol must match) and pytest
# into a venv under target/ (${MASON_ROS2ENV:-target/ros2env}; about 250 MB, made once and
# kept), then Mason's bridge package `mason_ros2` from ./ros2. Prints the venv's python.
# Usage: scripts/install-ros2.sh (from anywhere).
set -euo pipefail
cd "$(dirname "$0")/.."
ENV="${MASON_ROS2ENV:-target/ros2env}"
PY="$ENV/bin/python"
PINS=(
    "ros-rclpy[fastrtps]==9.1.2"
    "ros-std-msgs==5.5.1"
    "ros-geometry-msgs==5.5.1"
    "ros-visualization-msgs==5.5.1"
    "rosbags==0.11.9"
    "mcap-ros2-support==0.6.0"
    "eclipse-zenoh==1.10.2"
    "pytest==9.2.0"
)
# The pins are installed once: a stamp file holds the list they were installed from.
STAMP="$ENV/.mason-pins"
# The venv itself (python3-venv from Debian's packages if missing), made by the project's
# one venv script (with eclipse-zenoh, one of the pins).
MASON_PYENV="$ENV" scripts/install-python.sh eclipse-zenoh 1.10.2 >/dev/null
if [ "$(cat "$STAMP" 2>/dev/null)" != "${PINS[*]}" ]; then
    "$PY" -m pip install --quiet --disable-pip-version-check "${PINS[@]}" >&2
    echo "${PINS[*]}" >"$STAMP"
fi
# The bridge itself, every time (it is small): the sources of this checkout.
"$PY" -m pip install --quiet --disable-pip-version-check --no-deps --force-reinstall ./ros2 >&2
echo "$PY"
