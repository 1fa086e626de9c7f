"""Reads every rendered scene of a folder with `mason crew --image` and compares the reading with
the scene's ground truth: exact (grid, every blocked cell, robot and goal), refused (exit 2
with a reason), or WRONG (read, but not as rendered).

    python score.py MASON_BINARY SCENE_DIR [--lines]

Straight-down scenes get --grid W×H (or, with --lines, nothing: the grid is found from painted
lines when there are any); tilted ones get --grid and --corners from the ground truth.
"""
import json
import os
import subprocess
import sys
import tempfile
from collections import Counter


def read(mason, truth, folder, lines):
    w, h = truth["grid"]
    args = [mason, "crew", "--image", os.path.join(folder, truth["image"]), "--json"]
    if not (lines and truth["straight_down"] and truth["params"]["lines"]):
        args += ["--grid", f"{w}x{h}"]
    if not truth["straight_down"]:
        args += ["--corners", " ".join(f"{x},{y}" for x, y in truth["corners"])]
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
    lines = "--lines" in sys.argv
    tally = Counter()
    reasons = Counter()
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".json"):
            continue
        truth = json.load(open(os.path.join(folder, name)))
        verdict, why = read(mason, truth, folder, lines)
        tally[verdict] += 1
        if verdict != "exact":
            short = why.split(": ", 1)[-1]
            reasons[(verdict, short[:90])] += 1
            print(f"{name}: {verdict}: {why}")
    total = sum(tally.values())
    print(f"{total} scenes: " + ", ".join(f"{k} {v} ({100 * v / total:.1f} %)" for k, v in sorted(tally.items())))
    return 1 if tally["WRONG"] or tally["crash"] else 0


if __name__ == "__main__":
    sys.exit(main())
