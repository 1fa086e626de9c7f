"""Reads every rendered scene of a folder with `mason crew --image` and compares the reading with
the scene's ground truth: exact (grid, every blocked cell, robot and goal), refused (exit 2
with a reason), or WRONG (read, but not as rendered).

    python score.py MASON_BINARY SCENE_DIR [--lines | --no-grid] [--settle]

Straight-down scenes get --grid W×H (or, with --lines, nothing when lines are painted on their
floor: the grid is found from them; with --no-grid, nothing on any floor: one without lines
must be refused, "no grid"); tilted ones get --grid and --corners from the ground truth.

With --settle, an operator in the loop: when a view is refused for cells, the cells the refusal
names are settled as the ground truth has them (--blocked-cells, --free-cells) and the view is
read again, until it is read or refused for something else (a robot, a goal, the grid). The
cells settled are counted. A view then read wrongly was read wrongly in cells no refusal named.
"""
import json
import os
import re
import subprocess
import sys
import tempfile
from collections import Counter

# The cells a refusal names, past its pixel: "cell (x, y)", "cells (x, y) and (x, y)", and a
# region's "(cells (x, y) (x, y) …)".
CELL = re.compile(r"\((\d+), (\d+)\)")
# The refusals about cells (a robot's or a goal's names a cell too, but settles nothing).
CELL_REFUSAL = re.compile(
    r"cannot tell whether (it is|they are) blocked|look like the floor|a shadow on free floor|painted line between"
    r"|cannot tell where it stands"
)


def named_cells(reason):
    after = reason.split("): ", 1)[-1] if "pixel (" in reason else reason
    return {(int(x), int(y)) for x, y in CELL.findall(after)}


def read(mason, truth, folder, lines, settle=False):
    """(verdict, why), and with `settle` the number of cells settled after it."""
    settled = {}
    while True:
        verdict, why = read_once(mason, truth, folder, lines, settled)
        new = named_cells(why) - set(settled) if settle and verdict == "refused" else set()
        blocked = {tuple(c) for c in truth["blocked"]}
        w, h = truth["grid"]
        new = {c for c in new if c[0] < w and c[1] < h}
        if not new or not CELL_REFUSAL.search(why):
            return (verdict, why, len(settled)) if settle else (verdict, why)
        settled.update((c, c in blocked) for c in new)


def without_grid(truth, lines):
    """Whether the scene is read without --grid: straight down, with --lines on a floor with
    painted lines, with --no-grid (`lines` "all") on any floor."""
    painted = truth["params"].get("lines") or lines == "all"
    return bool(lines and truth["straight_down"] and painted)


def read_once(mason, truth, folder, lines, settled):
    w, h = truth["grid"]
    args = [mason, "crew", "--image", os.path.join(folder, truth["image"]), "--json"]
    if not without_grid(truth, lines):
        args += ["--grid", f"{w}x{h}"]
    if not truth["straight_down"]:
        args += ["--corners", " ".join(f"{x},{y}" for x, y in truth["corners"])]
    for flag, state in (("--blocked-cells", True), ("--free-cells", False)):
        cells = sorted(c for c, b in settled.items() if b == state)
        if cells:
            args += [flag, " ".join(f"{x},{y}" for x, y in cells)]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "read.map")
        p = subprocess.run(args + ["--save-map", out], capture_output=True, text=True)
        if p.returncode == 2:
            return "refused", p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "?"
        if p.returncode not in (0, 1):
            return "crash", p.stderr[-300:]
        got = json.loads(p.stdout)["reading"]
        rows = open(out).read().split("map\n", 1)[1].split()
    blocked = sorted([x, y] for y, row in enumerate(rows) for x, ch in enumerate(row) if ch == "@")
    problems = []
    if got["grid"] != [w, h]:
        problems.append(f"grid {got['grid']} for {[w, h]}")
    else:
        if blocked != sorted(truth["blocked"]):
            problems.append("blocked cells differ")
        for kind in ("robots", "goals"):
            a = sorted(m["cell"] for m in got[kind])
            if a != sorted(truth[kind]):
                problems.append(f"{kind} differ ({len(a)} read, {len(truth[kind])} rendered)")
    return ("exact", "") if not problems else ("WRONG", "; ".join(problems))


def main():
    mason, folder = sys.argv[1], sys.argv[2]
    lines = "all" if "--no-grid" in sys.argv else "--lines" in sys.argv
    settle = "--settle" in sys.argv
    tally = Counter()
    # The scenes read without --grid, by whether lines are painted on their floor.
    gridless = Counter()
    reasons = Counter()
    settled = Counter()
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".json"):
            continue
        truth = json.load(open(os.path.join(folder, name)))
        verdict, why, *cells = read(mason, truth, folder, lines, settle)
        tally[verdict] += 1
        if without_grid(truth, lines):
            painted = "with lines" if truth["params"].get("lines") else "without lines"
            no_grid = " (no grid)" if "no grid" in why else ""
            gridless[(painted, verdict + no_grid)] += 1
        if cells and cells[0]:
            settled[verdict] += cells[0]
            print(f"{name}: {verdict} after {cells[0]} cells settled")
        if verdict != "exact":
            short = why.split(": ", 1)[-1]
            reasons[(verdict, short[:90])] += 1
            print(f"{name}: {verdict}: {why}")
    total = sum(tally.values())
    print(f"{total} scenes: " + ", ".join(f"{k} {v} ({100 * v / total:.1f} %)" for k, v in sorted(tally.items())))
    if gridless:
        print("read without --grid: " + ", ".join(f"{k[0]}: {k[1]} {v}" for k, v in sorted(gridless.items())))
    if settle:
        print("cells settled: " + ", ".join(f"{k} {v}" for k, v in sorted(settled.items())))
    return 1 if tally["WRONG"] or tally["crash"] else 0


if __name__ == "__main__":
    sys.exit(main())
