#!/usr/bin/env bash
# The ROS 2 bridge and bags (#28): installs the ROS 2 venv (scripts/install-ros2.sh) and runs
# ros2/tests with pytest: the bridge's checks, the bags of `mason simulate --rosbag` read back
# by rosbags, mcap-ros2-support and rclpy, and the bridge end to end against `mason launch`
# (which needs a mason binary with the zenoh feature: ${MASON_BIN:-target/debug/mason}, built
# here with it if missing). ROS 2 discovery stays on this machine
# (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST, a domain id of the run's own). Extra arguments go
# to pytest. Run from anywhere.
set -euo pipefail
cd "$(dirname "$0")/.."
PY="$(scripts/install-ros2.sh | tail -n 1)"
export MASON_BIN="${MASON_BIN:-${CARGO_TARGET_DIR:-target}/debug/mason}"
PROBE="$([ -x "$MASON_BIN" ] && "$MASON_BIN" launch builtin:mbzirc --uavs 0 2>&1 || true)"
if [ ! -x "$MASON_BIN" ] || [[ "$PROBE" == *"zenoh feature"* ]]; then
    cargo build -p mason-cli --features zenoh
fi
MASON_BIN="$(realpath "$MASON_BIN")"
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
PY="$(realpath -s "$PY")"
cd ros2/tests
exec "$PY" -m pytest -q -p no:cacheprovider -s "$@" .
