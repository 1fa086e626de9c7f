"""`mason simulate --rosbag`: the bag read back by rosbags, mcap-ros2-support and rclpy, and
checked against the mission's JSON trace; bad output paths refused."""

import json
import os
import subprocess

import pytest

from bags import check_bag


def simulate(mason_bin, *args):
    return subprocess.run([mason_bin, "simulate", *args], capture_output=True, text=True)


@pytest.mark.parametrize("design,uavs,extra", [
    ("builtin:mbzirc", 3, []),
    ("builtin:thesis-2x5", 2, ["--coord", "windows", "--uav-fail", "1@100"]),
])
def test_a_simulated_mission_reads_back_as_its_trace(mason_bin, tmp_path, design, uavs, extra):
    bag = tmp_path / "bag"
    out = simulate(mason_bin, design, "--uavs", str(uavs), "--json", "--rosbag", str(bag), *extra)
    assert out.returncode in (0, 1), out.stderr
    doc = json.loads(out.stdout)
    bricks = doc["metrics"]["bricks_total"]
    summary = check_bag(bag, doc["events"], uavs, bricks)
    assert sorted(os.listdir(bag)) == ["bag_0.mcap", "metadata.yaml"]
    print(design, summary)


def test_the_same_seed_gives_the_same_bag(mason_bin, tmp_path):
    for name in ("a", "b"):
        (tmp_path / name).mkdir()
        out = simulate(mason_bin, "builtin:thesis-2x5", "--rosbag", str(tmp_path / name / "bag"))
        assert out.returncode in (0, 1), out.stderr
    for f in ("metadata.yaml", "bag_0.mcap"):
        assert (tmp_path / "a" / "bag" / f).read_bytes() == (tmp_path / "b" / "bag" / f).read_bytes()


def test_bad_bag_folders_are_refused(mason_bin, tmp_path):
    a_file = tmp_path / "file"
    a_file.write_text("keep")
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for target, words in [(a_file, "not a folder"), (fifo, "not a folder"),
                          (tmp_path / "missing" / "bag", "does not exist"), ("/dev/null", "not a folder")]:
        out = simulate(mason_bin, "builtin:thesis-2x5", "--rosbag", str(target))
        assert out.returncode == 2, (target, out.stderr)
        assert words in out.stderr and len(out.stderr.strip().splitlines()) == 1, out.stderr
    assert a_file.read_text() == "keep"
    out = simulate(mason_bin, "builtin:thesis-2x5", "--runs", "2", "--rosbag", str(tmp_path / "b"))
    assert out.returncode == 2 and "--rosbag" in out.stderr
    assert not (tmp_path / "b").exists()
