"""Time limits are honoured and Ctrl-C (SIGINT, KeyboardInterrupt) stops long calls.

The bounds asserted here are generous (a stop must come long before the call's own time
limit would end it); the measured latency is printed, and the README quotes it."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

import mason
from conftest import DATA

LONG = 60.0


def test_a_schedule_search_stops_at_its_time_limit():
    t0 = time.monotonic()
    s = mason.plan_schedule(mason.Wall.builtin("mbzirc"), time_limit=0.5)
    took = time.monotonic() - t0
    # The MBZIRC makespan never reaches its bound: the search runs to the limit.
    assert s.status == "timeout"
    assert took < LONG / 4, took


def test_a_crew_solve_stops_at_its_time_limit():
    grid, starts, goals = mason.crew.load_movingai(
        DATA / "crew-room.map", DATA / "crew-room.scen"
    )
    t0 = time.monotonic()
    sol = mason.crew.solve(grid, starts, goals, resolve="lacam", time_limit=0.3)
    assert time.monotonic() - t0 < LONG / 4
    assert sol.status in ("optimal", "feasible")


CALLS = {
    "schedule": "mason.plan_schedule(mason.Wall.builtin('mbzirc'), time_limit=LONG)",
    "monte_carlo": "mason.monte_carlo(mason.Wall.builtin('mbzirc'), runs=10**7, faults={'grasp_fail': 0.1})",
    "crew": textwrap.dedent(
        """
        import numpy as np
        rng = np.random.default_rng(1)
        grid = np.zeros((64, 64), dtype=bool)
        grid[10:54:8, 4:60] = True
        free = np.argwhere(~grid)[:, ::-1]
        pick = rng.permutation(len(free))
        starts, goals = free[pick[:1500]], free[pick[1500:3000]]
        mason.crew.solve(grid, starts, goals, resolve='lacam', time_limit=LONG)
        """
    ),
}


@pytest.mark.parametrize("what", sorted(CALLS))
def test_ctrl_c_stops_a_long_call_and_raises_keyboard_interrupt(what):
    script = f"import sys, mason\nLONG = {LONG}\nprint('ready', flush=True)\n{CALLS[what]}\nprint('finished', flush=True)\n"
    p = subprocess.Popen(
        [sys.executable, "-c", script],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert p.stdout.readline().strip() == "ready"
    time.sleep(1.5)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=LONG)
    latency = time.monotonic() - sent
    print(f"{what}: stopped {latency * 1e3:.0f} ms after SIGINT")
    assert "finished" not in out
    assert "KeyboardInterrupt" in err, err
    assert p.returncode != 0
    assert latency < LONG / 6, latency
