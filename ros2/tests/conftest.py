"""Shared set-up: the `mason` binary (MASON_BIN; built with the `zenoh` feature for the
bridge's tests), and ROS 2 discovery kept on this machine (ROS_AUTOMATIC_DISCOVERY_RANGE
LOCALHOST, a ROS_DOMAIN_ID of this run's own)."""

import os
import subprocess

import pytest

os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
os.environ.setdefault("ROS_DOMAIN_ID", str(1 + os.getpid() % 100))


def _require() -> bool:
    return os.environ.get("MASON_REQUIRE_ROS2") == "1"


@pytest.fixture(scope="session")
def mason_bin():
    path = os.environ.get("MASON_BIN")
    if not path or not os.access(path, os.X_OK):
        if _require():
            pytest.fail("MASON_BIN is not an executable mason binary")
        pytest.skip("set MASON_BIN to a mason binary")
    return path


@pytest.fixture(scope="session")
def mason_zenoh(mason_bin):
    """The mason binary, if it has the zenoh feature (`mason launch` needs it)."""
    out = subprocess.run([mason_bin, "launch", "builtin:mbzirc", "--uavs", "0"], capture_output=True, text=True)
    if "zenoh feature" in out.stderr:
        if _require():
            pytest.fail("MASON_BIN lacks the zenoh feature")
        pytest.skip("MASON_BIN lacks the zenoh feature")
    return mason_bin
