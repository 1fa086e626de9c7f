"""How much of each robot and goal a rendered view shows, and how close the robots (and the
goals) come to each other in the image: what a reader could see at best, from the scene's
geometry alone.

    target/venv-render/bin/python scripts/render-aerial/visibility.py SCENE_DIR [...] [--scores SCORES] [--tsv OUT]

For every scene rendered by render.py (families in FAMILIES, default arguments), the view is
drawn again with `render.draw_view` (the same random draws, so the same layout, light and
camera; the floor's corners are checked against the scene's JSON) and measured without
rendering:

- the **visible share** of each robot's top and of each goal: points spread over the top
  (a robot's top face, dome or cap; a goal's flat shape) are joined to the camera by a ray,
  and a point is hidden when a shelf or another robot stands in the way. A share under one
  half is a mark mostly hidden, which no reader can place with confidence;
- the **gap** between two robots, and between two goals, in image pixels: the distance between
  their silhouettes (the convex hull of the projected body). The layout keeps robots and
  goals 0.2 cell apart on the floor, but a tilted camera leans robots' bodies toward each
  other, and at 8 px a cell 0.2 cell is under 2 px, which blur and JPEG close.

With `--scores FILE` (score.py's output for the same folders: it names every view not read
exactly, with its verdict), the views are counted by verdict against the geometry: how many
refused views have a mark mostly hidden or marks within 2 px, so that their refusal is forced
by the scene rather than by the reader.

Scenes rendered by render_blender.py (families G-J) are left out: their geometry is not drawn
again here.
"""
import json
import math
import os
import sys
from collections import Counter

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render  # noqa: E402

HIDDEN = 0.5  # a mark showing less than this share of its top is mostly hidden
SAMPLES = 15  # points across a mark's top, per axis (inside its shape)


def shape_draws(view):
    """The draws scene_dict makes after the camera, in its order: a colour factor per robot,
    then a yaw per turned box; a turn per ellipse goal. Returns (robot yaws, goal yaws), in
    degrees."""
    rng, robot, goal = view["rng"], view["robot"], view["goal"]
    ryaw, gyaw = [], []
    for _ in view["robots"]:
        rng.uniform(0.85, 1.1)
        ryaw.append(float(rng.uniform(0, 90)) if robot["shape"] == "rotbox" else 0.0)
    for _ in view["goals"]:
        gyaw.append(float(rng.uniform(0, 180)) if goal["shape"] == "ellipse" else 0.0)
    return ryaw, gyaw


def rotate(x, y, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return c * x - s * y, s * x + c * y


def robot_parts(robot, cx, cy, yaw):
    """The robot's solids in world coordinates: ("box", centre, half sizes, yaw),
    ("cyl", centre, radius, z0, z1) or ("sphere", centre, radius)."""
    r, hgt, shape = robot["size"] / 2, robot["height"], robot["shape"]
    if shape in ("box", "boxdome"):
        parts = [("box", (cx, cy), (r, r, 0.0, hgt), 0.0)]
        if shape == "boxdome":
            parts.append(("sphere", (cx, cy, hgt), 0.5 * r))
        return parts
    if shape == "rotbox":
        half = r * math.sqrt(math.pi) / 2
        return [("box", (cx, cy), (half, half, 0.0, hgt), yaw)]
    parts = [("cyl", (cx, cy), r, 0.0, hgt)]
    if shape == "dome":
        parts.append(("sphere", (cx, cy, hgt), r))
    if shape == "puck":
        parts.append(("cyl", (cx, cy), 0.45 * r, hgt, 1.15 * hgt))
    return parts


def robot_top(robot, cx, cy, yaw):
    """Points over the robot's top as the camera sees it from above (N x 3)."""
    r, hgt, shape = robot["size"] / 2, robot["height"], robot["shape"]
    u = np.linspace(-1, 1, SAMPLES) * (1 - 1 / SAMPLES)
    gx, gy = [a.ravel() for a in np.meshgrid(u, u)]
    if shape in ("box", "boxdome", "rotbox"):
        half = r if shape != "rotbox" else r * math.sqrt(math.pi) / 2
        x, y = rotate(gx * half, gy * half, yaw)
        z = np.full(x.shape, hgt)
        if shape == "boxdome":
            d2 = x ** 2 + y ** 2
            z = np.where(d2 < (0.5 * r) ** 2, hgt + np.sqrt(np.maximum(0, (0.5 * r) ** 2 - d2)), z)
    else:
        keep = gx ** 2 + gy ** 2 <= 1
        x, y = gx[keep] * r, gy[keep] * r
        d2 = x ** 2 + y ** 2
        if shape == "dome":
            z = hgt + np.sqrt(np.maximum(0, r * r - d2))
        elif shape == "puck":
            z = np.where(d2 < (0.45 * r) ** 2, 1.15 * hgt, hgt)
        else:
            z = np.full(x.shape, hgt)
    return np.stack([x + cx, y + cy, z + 1e-6], axis=1)


def goal_top(goal, cx, cy, yaw, cell_px):
    """Points over the goal's flat shape on the floor (N x 3)."""
    r, shape = goal["size"] / 2, goal["shape"]
    u = np.linspace(-1, 1, SAMPLES) * (1 - 1 / SAMPLES)
    gx, gy = [a.ravel() for a in np.meshgrid(u, u)]
    if shape == "square":
        x, y = gx * r, gy * r
    elif shape == "diamond":
        x, y = rotate(gx * r / math.sqrt(2), gy * r / math.sqrt(2), 45.0)
    elif shape == "cross":
        keep = (np.abs(gy) <= 0.35) | (np.abs(gx) <= 0.35)
        x, y = gx[keep] * r, gy[keep] * r
    elif shape == "ellipse":
        keep = gx ** 2 + gy ** 2 <= 1
        x, y = rotate(gx[keep] * r, gy[keep] * max(0.6 * r, 1.75 / cell_px), yaw)
    else:  # disc, ring
        keep = gx ** 2 + gy ** 2 <= 1
        x, y = gx[keep] * r, gy[keep] * r
    return np.stack([x + cx, y + cy, np.full(np.shape(x), 0.004)], axis=1)


def hits(points, origin, part):
    """Whether each segment from a point to the camera passes through the solid."""
    d = origin[None, :] - points
    if part[0] == "box":
        _, (cx, cy), (hx, hy, z0, z1), yaw = part
        px, py = rotate(points[:, 0] - cx, points[:, 1] - cy, -yaw)
        dx, dy = rotate(d[:, 0], d[:, 1], -yaw)
        lo = np.stack([-hx - px, -hy - py, z0 - points[:, 2]], axis=1)
        hi = np.stack([hx - px, hy - py, z1 - points[:, 2]], axis=1)
        dd = np.stack([dx, dy, d[:, 2]], axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            t0, t1 = lo / dd, hi / dd
        tmin = np.where(np.abs(dd) < 1e-12, np.where((lo <= 0) & (hi >= 0), -np.inf, np.inf), np.minimum(t0, t1))
        tmax = np.where(np.abs(dd) < 1e-12, np.where((lo <= 0) & (hi >= 0), np.inf, -np.inf), np.maximum(t0, t1))
        enter, leave = tmin.max(axis=1), tmax.min(axis=1)
        return (enter <= leave) & (leave > 1e-9) & (enter < 1.0)
    if part[0] == "cyl":
        _, (cx, cy), r, z0, z1 = part
        ox, oy = points[:, 0] - cx, points[:, 1] - cy
        a = d[:, 0] ** 2 + d[:, 1] ** 2
        b = 2 * (ox * d[:, 0] + oy * d[:, 1])
        c = ox ** 2 + oy ** 2 - r * r
        disc = b * b - 4 * a * c
        ok = (disc >= 0) & (a > 1e-12)
        sq = np.sqrt(np.maximum(disc, 0))
        with np.errstate(divide="ignore", invalid="ignore"):
            ta, tb = (-b - sq) / (2 * a), (-b + sq) / (2 * a)
            za, zb = (z0 - points[:, 2]) / d[:, 2], (z1 - points[:, 2]) / d[:, 2]
        tz0, tz1 = np.minimum(za, zb), np.maximum(za, zb)
        enter, leave = np.maximum(ta, tz0), np.minimum(tb, tz1)
        return ok & (enter <= leave) & (leave > 1e-9) & (enter < 1.0)
    _, (cx, cy, cz), r = part
    o = points - np.array([cx, cy, cz])[None, :]
    a = (d * d).sum(axis=1)
    b = 2 * (o * d).sum(axis=1)
    c = (o * o).sum(axis=1) - r * r
    disc = b * b - 4 * a * c
    sq = np.sqrt(np.maximum(disc, 0))
    ta, tb = (-b - sq) / (2 * a), (-b + sq) / (2 * a)
    return (disc >= 0) & (tb > 1e-9) & (ta < 1.0)


def reach(part):
    """The part's centre on the floor and its radius there."""
    if part[0] == "box":
        return part[1], math.hypot(part[2][0], part[2][1])
    if part[0] == "cyl":
        return part[1], part[2]
    return part[1][:2], part[2]


def visible_share(points, origin, occluders, top):
    """The share of the points that see the camera past the occluders, of which only those
    whose floor disc lies near the points' rays (up to the height `top`) are tried."""
    centre = points[:, :2].mean(axis=0)
    spread = np.abs(points[:, :2] - centre).max()
    lean = (origin[:2] - centre) * top / max(origin[2] - top, 1e-6)
    seen = np.ones(len(points), bool)
    for part in occluders:
        (ox, oy), rad = reach(part)
        # The distance from the occluder's centre to the segment of the rays' floor
        # shadow from the points' centre up to `top`.
        q = np.array([ox, oy]) - centre
        t = np.clip(q @ lean / max(lean @ lean, 1e-12), 0, 1)
        if np.hypot(*(q - t * lean)) > rad + spread + 0.05:
            continue
        seen &= ~hits(points, origin, part)
    return float(seen.mean())


def hull(points):
    """Convex hull of 2-D points, counter-clockwise (monotone chain)."""
    pts = sorted(set(map(tuple, np.round(points, 4))))
    if len(pts) < 3:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def polygon_gap(a, b):
    """Distance between two convex polygons (0 when they overlap)."""
    for poly in (a, b):
        edges = np.roll(poly, -1, axis=0) - poly
        normals = np.stack([edges[:, 1], -edges[:, 0]], axis=1)
        pa, pb = a @ normals.T, b @ normals.T
        if np.any((pa.max(axis=0) < pb.min(axis=0)) | (pb.max(axis=0) < pa.min(axis=0))):
            break
    else:
        return 0.0

    def point_edges(p, poly):
        s, e = poly, np.roll(poly, -1, axis=0)
        v = e - s
        t = np.clip(((p[:, None, :] - s[None]) * v[None]).sum(-1) / np.maximum((v * v).sum(-1), 1e-12), 0, 1)
        near = s[None] + t[..., None] * v[None]
        return np.sqrt(((p[:, None, :] - near) ** 2).sum(-1)).min()

    return float(min(point_edges(a, b), point_edges(b, a)))


def silhouette(view, parts):
    """The image silhouette of solids: the hull of their projected rims."""
    cam = view["cam"]
    pts = []
    ang = np.linspace(0, 2 * math.pi, 48, endpoint=False)
    for part in parts:
        if part[0] == "box":
            _, (cx, cy), (hx, hy, z0, z1), yaw = part
            for z in (z0, z1):
                for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                    x, y = rotate(sx * hx, sy * hy, yaw)
                    pts.append((cx + x, cy + y, z))
        elif part[0] == "cyl":
            _, (cx, cy), r, z0, z1 = part
            for z in (z0, z1):
                pts += [(cx + r * math.cos(a), cy + r * math.sin(a), z) for a in ang]
        else:
            _, (cx, cy, cz), r = part
            pts += [(cx + r * math.cos(a) * math.cos(e), cy + r * math.sin(a) * math.cos(e), cz + r * math.sin(e))
                    for a in ang for e in np.linspace(0, math.pi / 2, 7)]
    return hull(np.array([render.project(cam, p) for p in pts]))


def goal_silhouette(view, goal, cx, cy, yaw):
    pts = goal_top(goal, cx, cy, yaw, view["cell_px"])
    return hull(np.array([render.project(view["cam"], p) for p in pts]))


def min_gap(shapes, centres, near):
    """The smallest gap between silhouettes of marks whose floor centres are within `near`."""
    best = math.inf
    for i in range(len(centres)):
        for j in range(i + 1, len(centres)):
            if math.dist(centres[i], centres[j]) < near:
                best = min(best, polygon_gap(shapes[i], shapes[j]))
    return best


def measure(folder, name):
    truth = json.load(open(os.path.join(folder, name)))
    if truth.get("family") not in render.FAMILIES or not truth.get("renderer", "").startswith("mitsuba"):
        return None
    args = render.arguments().parse_args(["-", "--family", truth["family"]])
    view = render.draw_view(args, truth["seed"])
    w, h = view["grid"]
    corners = [render.project(view["cam"], (x, h - y, 0.0)) for x, y in [(0, 0), (w, 0), (w, h), (0, h)]]
    if max(abs(a - b) for c, t in zip(corners, truth["corners"]) for a, b in zip(c, t)) > 0.02:
        return None  # rendered with other arguments than the defaults
    ryaw, gyaw = shape_draws(view)
    origin = np.array(view["cam"]["origin"], float)
    inset = view["fam"].get("shelf_inset", 0.02)
    shelves = [("box", (s["x"] + s["w"] / 2, h - (s["y"] + s["h"] / 2)),
                (s["w"] / 2 - inset, s["h"] / 2 - inset, 0.0, s["height"]), 0.0) for s in view["shelves"]]
    robot, goal = view["robot"], view["goal"]
    robots = [(cx, h - cy) for cx, cy in view["robots"]]
    goals = [(cx, h - cy) for cx, cy in view["goals"]]
    bodies = [robot_parts(robot, x, y, yaw) for (x, y), yaw in zip(robots, ryaw)]
    top = max([s[2][3] for s in shelves] + [robot["height"] * 1.15 + robot["size"] / 2])
    rvis = []
    for i, ((x, y), yaw) in enumerate(zip(robots, ryaw)):
        others = shelves + [p for j, b in enumerate(bodies) if j != i for p in b]
        rvis.append(visible_share(robot_top(robot, x, y, yaw), origin, others, top))
    every = shelves + [p for b in bodies for p in b]
    gvis = [visible_share(goal_top(goal, x, y, yaw, view["cell_px"]), origin, every, top)
            for (x, y), yaw in zip(goals, gyaw)]
    near = robot["size"] + 1.5
    rgap = min_gap([silhouette(view, b) for b in bodies], robots, near)
    ggap = min_gap([goal_silhouette(view, goal, x, y, yaw) for (x, y), yaw in zip(goals, gyaw)], goals,
                   goal["size"] + 1.5)
    return dict(name=name[:-5], robots=len(robots), cell_px=view["cell_px"], tilt=view["cam"]["tilt"],
                robot_vis=min(rvis, default=1.0), goal_vis=min(gvis, default=1.0),
                robots_hidden=sum(v < HIDDEN for v in rvis), goals_hidden=sum(v < HIDDEN for v in gvis),
                robot_gap=rgap, goal_gap=ggap, jpeg=int(truth["image"].endswith(".jpg")))


def scores(path):
    """Verdicts by view from score.py's output (`NAME.json: VERDICT: why` for each view not
    read exactly; the views it does not name were read exactly)."""
    out = {}
    for line in open(path):
        name, sep, rest = line.partition(".json: ")
        if sep and " after " not in rest.split(":")[0]:
            out[name.strip()] = rest.split(":")[0].strip()
    return out


def main():
    argv = sys.argv[1:]
    opts = {}
    for flag in ("--scores", "--tsv"):
        if flag in argv:
            k = argv.index(flag)
            opts[flag] = argv[k + 1]
            del argv[k:k + 2]
    rows = []
    for folder in argv:
        for name in sorted(os.listdir(folder)):
            if name.endswith(".json"):
                row = measure(folder, name)
                if row:
                    rows.append(row)
    if "--tsv" in opts:
        keys = list(rows[0]) if rows else []
        with open(opts["--tsv"], "w") as f:
            f.write("\t".join(keys) + "\n")
            for r in rows:
                f.write("\t".join(f"{r[k]:.3f}" if isinstance(r[k], float) else str(r[k]) for k in keys) + "\n")

    def forced(r):
        why = []
        if r["robots_hidden"]:
            why.append("a robot mostly hidden")
        if r["goals_hidden"]:
            why.append("a goal mostly hidden")
        if r["robot_gap"] < 2.0:
            why.append("robots under 2 px apart")
        if r["goal_gap"] < 2.0:
            why.append("goals under 2 px apart")
        return why

    print(f"{len(rows)} scenes measured")
    tally = Counter(" and ".join(forced(r)) or "every mark shows, none within 2 px" for r in rows)
    for k, v in tally.most_common():
        print(f"  {v:5d}  {k}")
    if "--scores" in opts:
        verdicts = scores(opts["--scores"])
        table = Counter()
        for r in rows:
            table[(verdicts.get(r["name"], "exact"), bool(forced(r)))] += 1
        print("by verdict (the scene shows every mark, none within 2 px / it does not):")
        for v in sorted({k[0] for k in table}):
            print(f"  {v:8s} {table[(v, False)]:5d} / {table[(v, True)]:5d}")
        # Read exactly, by pixels per cell and camera (the README's "what to expect").
        exact = lambda rs: f"{sum(verdicts.get(r['name'], 'exact') == 'exact' for r in rs)} of {len(rs)}"
        print("read exactly, by pixels per cell: straight down | tilted | all | all showing every mark")
        for lo, hi in ((8, 12), (12, 16), (16, 24), (24, 40)):
            rs = [r for r in rows if lo <= r["cell_px"] < hi or (hi == 40 and r["cell_px"] >= 40)]
            print(f"  {lo}-{hi}: {exact([r for r in rs if r['tilt'] == 0])} | "
                  f"{exact([r for r in rs if r['tilt'] != 0])} | {exact(rs)} | "
                  f"{exact([r for r in rs if not forced(r)])}")
        print(f"  PNG: {exact([r for r in rows if not r['jpeg']])}, JPEG: {exact([r for r in rows if r['jpeg']])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
