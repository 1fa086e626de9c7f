"""Where the aerial reader stands on rendered scenes, beyond score.py's verdicts: why the refused
scenes were refused (the first reason, in kinds), whether the cell a refusal names is blocked or
free in the truth, and how far the robots' and goals' centres read are from the rendered ones.

    python census.py MASON_BINARY SCENE_DIR [SCENE_DIR ...] [--audit]

With --audit, each scene is also read with `mason crew --audit` (past every refusal about a
cell) and the reading compared with the truth: the cells read wrongly that no refusal names
are latent errors, which only the refusal of another cell keeps out of the normal reading;
so are robots and goals read wrongly there (since issue #29's eleventh round).

The centres come from the scene's JSON (`robot_centres`, `goal_centres`, written by render.py
since issue #29's tenth round); for scenes rendered before, render.py's layout is drawn again
from the family and seed (the same random draws as the render, so the same layout), which needs
render.py's venv (`target/venv-render/bin/python census.py ...`); without it those scenes' centres
are left out. Scenes rendered by render_blender.py (families G-J) have no centres.
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile
from collections import Counter

KINDS = [
    ("a half-covered cell no leaning top explains", r"no neighbour.s leaning top explains"),
    ("a covered cell a top may cover almost whole", r"may cover it almost whole"),
    ("a covered cell on the floor's far edge", r"on the floor's edge is covered"),
    ("a run's far cell a top could cover whole", r"cover it whole"),
    ("a free cell unlike the floor", r"would be free but do(es)? not look"),
    ("a shadow behind lit floor, seen from the sun", r"lies behind lit floor"),
    ("a shadow with no caster", r"shadow on free floor"),
    ("a piece too small", r"too large for noise|too small"),
    ("touching", r"touching"),
    ("a mark on a cell border", r"on the border of cell"),
    ("fewer goals than robots", r"but only .* goals"),
    ("a colour it cannot tell", r"neither the robo"),
    ("a cell showing no floor", r"shows no pixel of floor"),
    ("a mark on a blocked cell", r"which an obstacle covers"),
    ("a painted line that does not show", r"painted line between"),
    ("more goals than robots", r"give --spare-goals"),
    ("a robot taken for a shelf", r"stand against the shelf"),
    ("a run whose base may be a cell nearer", r"its face showing there"),
    ("a top where another's shadow falls", r"casts its shadow, seen from the sun"),
]


# The kinds whose reason names a cell the reading doubts (not a mark's cell).
CELL_KINDS = {name for name, _ in KINDS[:7]} | {"a cell showing no floor", "a painted line that does not show",
                                                "a run whose base may be a cell nearer",
                                                "a top where another's shadow falls"}


def kind_of(reason):
    for name, pattern in KINDS:
        if re.search(pattern, reason):
            return name
    return "other: " + reason.split(": ")[-1][:60]


def layout_again(truth):
    """The robots' and goals' centres of a scene rendered by render.py with its default
    arguments, drawn again (None when they cannot be)."""
    try:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import render
    except ImportError:
        return None
    if truth.get("family") not in render.FAMILIES:
        return None
    args = render.arguments().parse_args(["-", "--family", truth["family"]])
    _, _, grid, cell_px, _, _, (_, _, robots, goals) = render.draw_scene(args, truth["seed"])
    same = list(grid) == truth["grid"] and abs(cell_px - truth["cell_px"]) < 1e-9
    if not same or [[int(x), int(y)] for x, y in robots] != truth["robots"]:
        return None  # rendered with other arguments than the defaults
    return robots, goals


def audit(mason, folder, truth, args):
    """The cells of the audited reading that differ from the truth and that no refusal names,
    whether a refusal for a region was found, and the robots and goals read wrongly (their
    cells: the rendered ones missing, the read ones extra): None when the audit stops at a
    robot's or goal's reason."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "audit.map")
        p = subprocess.run(args + ["--audit", "--save-map", out], capture_output=True, text=True)
        if not os.path.exists(out):
            return None
        rows = open(out).read().split("map\n", 1)[1].split()
    read = {(x, y) for y, row in enumerate(rows) for x, ch in enumerate(row) if ch == "@"}
    rendered = {tuple(c) for c in truth["blocked"]}
    # The cells the refusals name ("cell (x, y)", or a painted line "between cells (x, y) and
    # (x', y')").
    named = {
        (int(m.group(1)), int(m.group(2)))
        for line in p.stderr.splitlines()
        if line.startswith("doubt: ")
        for m in re.finditer(r"(?:cells? |and )\((\d+), (\d+)\)", line)
    }
    # A shadow nothing casts and free cells side by side unlike the floor around them are
    # refused for a region (a shelf of the floor's colour somewhere near), named by one cell.
    region = any(
        "shadow on free floor" in line or "cells side by side" in line
        for line in p.stderr.splitlines()
        if line.startswith("doubt: ")
    )
    reading = json.loads(p.stdout)["reading"]
    marks = {}
    for kind in ("robots", "goals"):
        got = sorted(tuple(m["cell"]) for m in reading[kind])
        want = sorted(tuple(c) for c in truth[kind])
        if got != want:
            marks[kind] = (sorted(set(want) - set(got)), sorted(set(got) - set(want)))
    return sorted((read ^ rendered) - named), region, marks


def main():
    flags = [a for a in sys.argv[1:] if a.startswith("--")]
    mason, *folders = [a for a in sys.argv[1:] if not a.startswith("--")]
    audits = Counter()
    latent = []
    latent_marks = []
    verdicts, kinds, at_cell = Counter(), Counter(), Counter()
    errors = {"robots": [], "goals": []}
    for folder in folders:
        for name in sorted(os.listdir(folder)):
            if not name.endswith(".json"):
                continue
            truth = json.load(open(os.path.join(folder, name)))
            w, h = truth["grid"]
            args = [mason, "crew", "--image", os.path.join(folder, truth["image"]), "--json", "--grid", f"{w}x{h}"]
            if not truth["straight_down"]:
                args += ["--corners", " ".join(f"{x},{y}" for x, y in truth["corners"])]
            p = subprocess.run(args, capture_output=True, text=True)
            if "--audit" in flags:
                found = audit(mason, folder, truth, args)
                audits["stopped at a robot's or goal's reason" if found is None else "read"] += 1
                if found and found[0]:
                    latent.append((name[:-5], *found[:2]))
                if found and found[2]:
                    latent_marks.append((name[:-5], found[2]))
            if p.returncode == 2:
                verdicts["refused"] += 1
                reason = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "?"
                kind = kind_of(reason)
                kinds[kind] += 1
                cell = re.search(r"cell \((\d+), (\d+)\)", reason)
                if cell and kind in CELL_KINDS:
                    blocked = [int(cell.group(1)), int(cell.group(2))] in truth["blocked"]
                    at_cell[(kind, "blocked" if blocked else "free")] += 1
                continue
            if p.returncode not in (0, 1):
                verdicts["crash"] += 1
                continue
            verdicts["read"] += 1
            reading = json.loads(p.stdout)["reading"]
            if "robot_centres" in truth:
                centres = truth["robot_centres"], truth["goal_centres"]
            else:
                centres = layout_again(truth)
            if centres is None:
                continue
            for kind, rendered in zip(("robots", "goals"), centres):
                for mark in reading[kind]:
                    u, v = mark["floor"]
                    errors[kind].append(min(math.hypot(x - u, y - v) for x, y in rendered))
    total = sum(verdicts.values())
    print(f"{total} scenes: " + ", ".join(f"{k} {v}" for k, v in sorted(verdicts.items())) + " (score.py tells exact from wrong)")
    print("refused, first reason:")
    for kind, n in kinds.most_common():
        cells = ", ".join(f"{at_cell[(kind, t)]} {t}" for t in ("blocked", "free") if at_cell[(kind, t)])
        print(f"  {n:4d}  {kind}" + (f"  (the cell named: {cells} in the truth)" if cells else ""))
    if "--audit" in flags:
        print("audited past the cells' refusals: " + ", ".join(f"{k} {v}" for k, v in sorted(audits.items())))
        for guarded, title in [
            (True, "with a refusal for a region (a shadow nothing casts, cells unlike the floor around them)"),
            (False, "with no refusal for a region: latent errors"),
        ]:
            some = [(scene, cells) for scene, cells, region in latent if region == guarded]
            print(f"  cells read wrongly that no refusal names, {title}: {sum(len(c) for _, c in some)} in {len(some)} scenes")
            for scene, cells in some:
                print(f"    {scene}: {cells}")
        print(f"  robots or goals read wrongly past the cells' refusals (latent errors of the marks): {len(latent_marks)} scenes")
        for scene, marks in latent_marks:
            print(f"    {scene}: " + "; ".join(f"{k} missing {m}, extra {e}" for k, (m, e) in marks.items()))
    for kind, errs in errors.items():
        if not errs:
            continue
        errs.sort()
        q = lambda f: errs[min(len(errs) - 1, int(f * len(errs)))]
        print(f"{kind}' centres read ({len(errs)}), distance from the rendered centre in cells: "
              f"median {q(0.5):.3f}, 90 % {q(0.9):.3f}, 99 % {q(0.99):.3f}, most {errs[-1]:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
