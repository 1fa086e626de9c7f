"""Renders aerial views of a robot floor with Blender (Cycles, CPU): a second renderer, independent
of render.py's Mitsuba 3, with the same ground-truth contract (score.py reads both).

    blender -b --factory-startup -noaudio -P render_blender.py -- OUT_DIR --family G --seeds 0-59

(scripts/render-aerial/install-blender.sh installs Debian's blender with python3-numpy and
python3-pil, which Blender's Python imports.)

Geometry is render.py's: a floor of W x H cells (1 world unit per cell) at z = 0 (z up); cell
(x, y) (column x, row y) covers world [x, x+1] x [H-y-1, H-y], so a camera looking straight down
with image up along +y sees row 0 at the top. Everything else is Blender's own: Principled BSDF
materials, procedural floors (noise, brick-node tiles not always aligned with the cells,
painted lines from math nodes, glossy epoxy), shelves with goods on top, hexagonal-prism,
lying-capsule, frustum, bevelled-box and lidar-puck robots, ring, star, X-cross and target
goals, a sun lamp of a given angular size under a Nishita sky or ceiling area lights, a
perspective camera straight down or tilted and rolled, then an automatic exposure, a tone
curve, white balance, vignetting, blur, noise and JPEG in numpy. Marks whose centre a shelf
hides from the camera are not placed (each hidden goal drops a robot too), so the truth lists
only what can be seen. Everything random comes from the family and the seed.
"""
import argparse
import json
import math
import os
import sys
import tempfile
import time

import bmesh
import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Matrix, Vector
from PIL import Image

FAMILIES = {
    # G: the first Blender family (held out for the reader of issue #29's fourth round).
    "G": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Concrete, light epoxy, blue-grey, warm beige, dark asphalt, pale green-grey.
        floors=((0.52, 0.52, 0.50), (0.74, 0.74, 0.72), (0.42, 0.46, 0.52), (0.70, 0.62, 0.50),
                (0.24, 0.24, 0.25), (0.58, 0.62, 0.56)),
        # Steel blue, amber, slate teal, purple, pale blue-grey, anthracite, white.
        shelf_colours=((0.08, 0.20, 0.55), (0.85, 0.62, 0.05), (0.20, 0.35, 0.45), (0.30, 0.12, 0.45),
                       (0.55, 0.60, 0.70), (0.07, 0.07, 0.08), (0.85, 0.85, 0.83)),
        goods_colour=(0.50, 0.36, 0.18),  # cardboard
        shelf_height=(0.3, 1.6), shelf_inset=(0.02, 0.07), camera_ratio=(1.6, 6.0), tilt_max=35.0),
    # H: the second Blender family (rendered while the fifth round's reader was being written,
    # held out from it, scored once with it): other floors and shelf colours, taller shelves
    # inset further, nearer and farther cameras.
    "H": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Mid blue-grey, light grey, warm tan, dark green-grey, sand.
        floors=((0.35, 0.38, 0.42), (0.80, 0.80, 0.79), (0.62, 0.55, 0.45), (0.30, 0.34, 0.30),
                (0.76, 0.70, 0.58)),
        # Safety orange, light grey, dark navy, signal yellow, walnut brown, grey-green.
        shelf_colours=((0.90, 0.40, 0.05), (0.70, 0.70, 0.70), (0.05, 0.08, 0.30), (0.85, 0.80, 0.10),
                       (0.35, 0.22, 0.12), (0.40, 0.45, 0.38)),
        goods_colour=(0.62, 0.48, 0.30),  # lighter cardboard
        shelf_height=(0.4, 2.0), shelf_inset=(0.03, 0.10), camera_ratio=(1.4, 5.0), tilt_max=30.0),
    # I: the third Blender family (rendered at the start of the sixth round, held out from it,
    # scored once with its final reader): other floors and shelf colours, other robot and goal
    # sizes and reds and greens, a higher sun of other softness, other exposure, noise, blur
    # and JPEG quality. Keys absent from G and H take the defaults in render_one.
    "I": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Warm light grey, dark blue-grey, khaki, cool pale concrete, brown-grey.
        floors=((0.66, 0.64, 0.60), (0.22, 0.25, 0.30), (0.55, 0.52, 0.40), (0.60, 0.63, 0.66),
                (0.45, 0.40, 0.36)),
        # Royal blue, dark grey, cream, dark teal, mauve, light tan.
        shelf_colours=((0.10, 0.25, 0.70), (0.25, 0.25, 0.27), (0.85, 0.80, 0.65), (0.05, 0.30, 0.32),
                       (0.50, 0.35, 0.45), (0.75, 0.60, 0.40)),
        goods_colour=(0.55, 0.45, 0.35),  # greyer cardboard
        shelf_height=(0.3, 1.8), shelf_inset=(0.02, 0.09), camera_ratio=(1.8, 4.5), tilt_max=25.0,
        robot_size=(0.35, 0.85), big_robot_size=(1.2, 1.6), goal_size=(0.35, 0.85),
        robot_rgb=((0.45, 0.9), (0.0, 0.15), (0.02, 0.15)), goal_rgb=((0.02, 0.2), (0.3, 0.7), (0.02, 0.25)),
        sun_elevation=(35.0, 85.0), sun_angle=(1.0, 8.0), exposure=(0.14, 0.30),
        noise_max=0.03, blur_max=1.3, jpeg_quality=(55, 96)),
    # J: the fourth Blender family (rendered at the start of the seventh round, held out from
    # it, scored once with its final reader): other floors, shelves of colours near some of
    # them, other robot and goal sizes, reds and greens, a sun of other height and softness,
    # other exposure, noise, blur and JPEG quality, cameras nearer and tilted further. Only
    # keys G, H and I already know, so those render unchanged.
    "J": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Mid warm grey, pale blue, olive grey, light beige, charcoal.
        floors=((0.50, 0.47, 0.44), (0.62, 0.68, 0.74), (0.42, 0.44, 0.34), (0.78, 0.74, 0.66),
                (0.18, 0.18, 0.20)),
        # Light warm grey (near the beige and warm grey floors), pale steel blue (near the pale
        # blue floor), olive drab, forest green-grey, dark charcoal (near the charcoal floor),
        # bright blue, ochre.
        shelf_colours=((0.70, 0.66, 0.60), (0.55, 0.62, 0.72), (0.35, 0.36, 0.20), (0.20, 0.30, 0.25),
                       (0.12, 0.12, 0.13), (0.05, 0.35, 0.80), (0.75, 0.55, 0.15)),
        goods_colour=(0.58, 0.42, 0.26),
        shelf_height=(0.25, 1.7), shelf_inset=(0.02, 0.08), camera_ratio=(1.5, 4.0), tilt_max=32.0,
        robot_size=(0.38, 0.82), big_robot_size=(1.25, 1.65), goal_size=(0.38, 0.82),
        robot_rgb=((0.5, 0.95), (0.0, 0.1), (0.0, 0.12)), goal_rgb=((0.0, 0.18), (0.32, 0.72), (0.0, 0.3)),
        sun_elevation=(30.0, 75.0), sun_angle=(0.8, 10.0), exposure=(0.15, 0.31),
        noise_max=0.028, blur_max=1.2, jpeg_quality=(58, 96)),
    # 3 (a digit, as render.py's held-out families after z): the fifth Blender family, held out
    # after issue #29's thirty-first round (rendered once its reader was finished, scored once):
    # other floors and shelf colours (a pale lilac and an off-white near the pale floors), other
    # sizes, reds and greens, sun, exposure, noise, blur and JPEG quality. Only keys G-J know.
    "3": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Dark teal-grey, pale warm grey, mid brown, light green-grey, mid grey.
        floors=((0.25, 0.32, 0.34), (0.72, 0.70, 0.66), (0.46, 0.36, 0.28), (0.64, 0.68, 0.60),
                (0.50, 0.50, 0.52)),
        # Brick red, pale lilac, dark olive, sky blue, off-white, dark grey.
        shelf_colours=((0.55, 0.18, 0.12), (0.70, 0.64, 0.76), (0.28, 0.30, 0.14), (0.35, 0.60, 0.85),
                       (0.86, 0.85, 0.80), (0.20, 0.20, 0.22)),
        goods_colour=(0.60, 0.46, 0.30),
        shelf_height=(0.3, 1.9), shelf_inset=(0.02, 0.08), camera_ratio=(1.5, 5.0), tilt_max=30.0,
        robot_size=(0.4, 0.8), big_robot_size=(1.2, 1.6), goal_size=(0.4, 0.8),
        robot_rgb=((0.5, 0.9), (0.0, 0.12), (0.0, 0.12)), goal_rgb=((0.0, 0.2), (0.35, 0.7), (0.02, 0.25)),
        sun_elevation=(30.0, 80.0), sun_angle=(1.0, 9.0), exposure=(0.15, 0.30),
        noise_max=0.025, blur_max=1.1, jpeg_quality=(60, 96)),
    # 5: the sixth Blender family, held out after issue #29's thirty-first round's last rule
    # (rendered once that reader was finished, scored once): other floors and shelf colours (a
    # cream near the tan floor, a pale blue and a steel grey near the concrete and slate), other
    # sizes, reds and greens, sun, exposure, noise, blur and JPEG quality. Only keys G-J know.
    "5": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Light concrete, warm tan, dark slate, pale sage, mid grey-brown.
        floors=((0.70, 0.70, 0.68), (0.66, 0.58, 0.46), (0.22, 0.26, 0.30), (0.62, 0.66, 0.58),
                (0.48, 0.44, 0.40)),
        # Cream, steel grey, dark green, orange, pale blue, plum.
        shelf_colours=((0.88, 0.84, 0.72), (0.45, 0.48, 0.52), (0.10, 0.30, 0.18), (0.90, 0.45, 0.10),
                       (0.60, 0.70, 0.82), (0.40, 0.18, 0.35)),
        goods_colour=(0.56, 0.44, 0.30),
        shelf_height=(0.3, 1.8), shelf_inset=(0.02, 0.08), camera_ratio=(1.6, 5.0), tilt_max=32.0,
        robot_size=(0.38, 0.82), big_robot_size=(1.2, 1.6), goal_size=(0.38, 0.82),
        robot_rgb=((0.5, 0.92), (0.0, 0.12), (0.0, 0.14)), goal_rgb=((0.0, 0.2), (0.35, 0.72), (0.0, 0.25)),
        sun_elevation=(30.0, 82.0), sun_angle=(1.0, 9.0), exposure=(0.15, 0.30),
        noise_max=0.026, blur_max=1.1, jpeg_quality=(60, 96)),
    # 6: the seventh Blender family, held out after issue #29's thirty-first round (rendered
    # once its reader was finished, scored once): pale floors and shelves near their colours
    # (off-white, light grey-blue, beige) under a high sun, whose shadows are short: the case
    # that family 3's 30016 was read wrongly in, made to look for more. It found them: 4 of
    # its 40 views are read wrongly (see scripts/render-aerial/README.md).
    "6": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Pale grey, warm light grey, cool grey, dark grey, cream.
        floors=((0.75, 0.74, 0.70), (0.68, 0.66, 0.62), (0.58, 0.60, 0.62), (0.40, 0.40, 0.42),
                (0.80, 0.76, 0.68)),
        # Off-white, light grey-blue, beige, slate, red, blue.
        shelf_colours=((0.84, 0.83, 0.80), (0.62, 0.64, 0.66), (0.74, 0.70, 0.62), (0.30, 0.32, 0.36),
                       (0.70, 0.20, 0.15), (0.20, 0.45, 0.70)),
        goods_colour=(0.58, 0.45, 0.30),
        shelf_height=(0.3, 1.8), shelf_inset=(0.02, 0.08), camera_ratio=(1.6, 5.0), tilt_max=30.0,
        robot_size=(0.38, 0.82), big_robot_size=(1.2, 1.6), goal_size=(0.38, 0.82),
        robot_rgb=((0.5, 0.92), (0.0, 0.12), (0.0, 0.14)), goal_rgb=((0.0, 0.2), (0.35, 0.72), (0.0, 0.25)),
        sun_elevation=(50.0, 88.0), sun_angle=(1.0, 9.0), exposure=(0.15, 0.30),
        noise_max=0.026, blur_max=1.1, jpeg_quality=(60, 96)),
    # 7: the eighth Blender family, held out after issue #29's thirty-second round (painted
    # lines measured by colour, faint lines against the cells' middles; rendered once that
    # reader was finished, scored once): other floors and shelf colours (a light warm grey and a
    # pale grey-blue near two of the floors), other sizes, reds and greens, sun, exposure,
    # noise, blur and JPEG quality. Only keys G-J know.
    "7": dict(
        robot_shapes=("hex", "capsule", "frustum", "roundbox", "lidar"),
        goal_shapes=("ring", "star", "xcross", "target", "disc"),
        # Mid warm grey, pale blue-grey, dark brown, light sage, sandy beige.
        floors=((0.55, 0.52, 0.48), (0.70, 0.74, 0.78), (0.28, 0.22, 0.18), (0.66, 0.70, 0.62),
                (0.78, 0.72, 0.60)),
        # Teal, light warm grey, mustard, charcoal, maroon, pale grey-blue.
        shelf_colours=((0.10, 0.45, 0.45), (0.72, 0.70, 0.66), (0.80, 0.65, 0.15), (0.15, 0.15, 0.17),
                       (0.45, 0.10, 0.12), (0.66, 0.70, 0.76)),
        goods_colour=(0.54, 0.42, 0.28),
        shelf_height=(0.3, 1.8), shelf_inset=(0.02, 0.08), camera_ratio=(1.6, 5.0), tilt_max=32.0,
        robot_size=(0.4, 0.8), big_robot_size=(1.2, 1.6), goal_size=(0.4, 0.8),
        robot_rgb=((0.5, 0.92), (0.0, 0.12), (0.0, 0.14)), goal_rgb=((0.0, 0.2), (0.35, 0.72), (0.0, 0.25)),
        sun_elevation=(35.0, 85.0), sun_angle=(1.0, 9.0), exposure=(0.15, 0.30),
        noise_max=0.026, blur_max=1.1, jpeg_quality=(60, 96)),
}


def parse_range(text, cast=int):
    lo, _, hi = text.partition("-")
    return cast(lo), cast(hi or lo)


# ---------------------------------------------------------------- layout

def pick_layout(rng, w, h, n_robots, fam, robot_reach, goal_reach):
    """Shelves (rectangles of cells: aisles of racks or scattered blocks), then robot and goal
    centres (cell coordinates, y down) that touch nothing."""
    blocked = np.zeros((h, w), bool)
    shelves = []

    def add(x, y, sw, sh):
        if x < 0 or y < 0 or x + sw > w or y + sh > h:
            return
        if blocked[max(0, y - 1):y + sh + 1, max(0, x - 1):x + sw + 1].any():
            return
        blocked[y:y + sh, x:x + sw] = True
        shelves.append(dict(x=x, y=y, w=sw, h=sh, height=float(rng.uniform(*fam["shelf_height"])),
                            colour=list(fam["shelf_colours"][int(rng.integers(len(fam["shelf_colours"])))]),
                            goods=bool(rng.random() < 0.25)))

    if rng.random() < 0.45:
        # Aisles: rows (or columns) of racks, 1 or 2 cells deep, with gaps to cross them.
        horizontal = rng.random() < 0.5
        depth = int(rng.integers(1, 3))
        along, across = (w, h) if horizontal else (h, w)
        pitch = depth + int(rng.integers(2, 4))
        start = int(rng.integers(1, 3))
        for a in range(start, across - depth, pitch):
            pos = int(rng.integers(1, 3))
            while pos < along - 2:
                length = int(rng.integers(2, 7))
                length = min(length, along - 1 - pos)
                if length >= 2 and rng.random() < 0.8:
                    if horizontal:
                        add(pos, a, length, depth)
                    else:
                        add(a, pos, depth, length)
                pos += length + int(rng.integers(1, 3))
    else:
        for _ in range(int(rng.integers(0, max(2, w * h // 22)))):
            length = int(rng.integers(1, 6))
            depth = 1 if rng.random() < 0.75 else 2
            sw, sh = (length, depth) if rng.random() < 0.5 else (depth, length)
            add(int(rng.integers(0, max(1, w - sw + 1))), int(rng.integers(0, max(1, h - sh + 1))), sw, sh)

    free = [(x, y) for y in range(h) for x in range(w) if not blocked[y, x]]
    order = rng.permutation(len(free))
    robots, goals, taken = [], [], []

    def fits(cx, cy, reach):
        for ox, oy, orch in taken:
            if abs(cx - ox) < reach + orch and abs(cy - oy) < reach + orch:
                return False
        x0, x1 = int(math.floor(cx - reach)), int(math.floor(cx + reach))
        y0, y1 = int(math.floor(cy - reach)), int(math.floor(cy + reach))
        if x0 < 0 or y0 < 0 or x1 >= w or y1 >= h:
            return False
        return not blocked[y0:y1 + 1, x0:x1 + 1].any()

    for i in order:
        if len(robots) == n_robots and len(goals) == n_robots:
            break
        x, y = free[i]
        want_robot = len(robots) < n_robots and (len(goals) >= n_robots or rng.random() < 0.5)
        reach = robot_reach if want_robot else goal_reach
        cx = x + 0.5 + rng.uniform(-0.24, 0.24)
        cy = y + 0.5 + rng.uniform(-0.24, 0.24)
        if not fits(cx, cy, reach):
            continue
        taken.append((cx, cy, reach))
        (robots if want_robot else goals).append((cx, cy))
    return blocked, shelves, robots, goals


# ---------------------------------------------------------------- camera

def look_at(origin, target, roll):
    """Camera-to-world matrix: local -Z along the view, +Y the image's up, rolled about the view."""
    f = (target - origin).normalized()
    right = f.cross(Vector((0.0, 1.0, 0.0)))
    if right.length < 1e-9:
        right = Vector((1.0, 0.0, 0.0))
    right.normalize()
    up = right.cross(f)
    if roll:
        rot = Matrix.Rotation(roll, 3, f)
        right, up = rot @ right, rot @ up
    m = Matrix.Identity(4)
    for i in range(3):
        m[i][0], m[i][1], m[i][2], m[i][3] = right[i], up[i], -f[i], origin[i]
    return m


def plan_camera(rng, w, h, cell_px, fam, straight):
    """Position, orientation, horizontal field of view and image size."""
    ratio = rng.uniform(*fam["camera_ratio"])
    dist = ratio * max(w, h)
    centre = Vector((w / 2, h / 2, 0.0))
    if straight:
        origin = centre + Vector((0, 0, dist))
        mat = look_at(origin, centre, 0.0)
        fov = 2 * math.atan((w / 2) / dist)
        return dict(matrix=mat, fov=fov, size=(int(round(w * cell_px)), int(round(h * cell_px))),
                    tilt=0.0, roll=0.0, height=dist)
    tilt = math.radians(rng.uniform(6.0, fam["tilt_max"]))
    azim = rng.uniform(0, 2 * math.pi)
    target = centre + Vector((rng.uniform(-0.08, 0.08) * w, rng.uniform(-0.08, 0.08) * h, 0.0))
    origin = target + Vector((math.sin(tilt) * math.cos(azim), math.sin(tilt) * math.sin(azim), math.cos(tilt))) * dist
    roll = rng.uniform(-math.pi, math.pi) if rng.random() < 0.3 else rng.uniform(-0.35, 0.35)
    mat = look_at(origin, target, roll)
    inv = mat.inverted()
    pts = []
    for x, y in ((0, h), (w, h), (w, 0), (0, 0)):
        q = inv @ Vector((x, y, 0.0))
        pts.append((q.x / -q.z, q.y / -q.z))
    pts = np.array(pts)
    margin = rng.uniform(1.04, 1.15)
    half_x, half_y = np.abs(pts[:, 0]).max() * margin, np.abs(pts[:, 1]).max() * margin
    edges = sum(math.dist(pts[i], pts[(i + 1) % 4]) for i in range(4))
    scale = cell_px / (edges / (2 * (w + h)))  # pixels per unit of the normalised image plane
    return dict(matrix=mat, fov=2 * math.atan(half_x), size=(int(2 * half_x * scale), int(2 * half_y * scale)),
                tilt=math.degrees(tilt), roll=math.degrees(roll), height=origin.z)


# ---------------------------------------------------------------- materials

def principled(name, rgb, rough, metallic=0.0, spec=0.5, coat=0.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    b = mat.node_tree.nodes["Principled BSDF"]
    b.inputs["Base Color"].default_value = (*[float(c) for c in rgb], 1.0)
    b.inputs["Roughness"].default_value = float(rough)
    b.inputs["Metallic"].default_value = float(metallic)
    b.inputs["Specular"].default_value = float(spec)
    b.inputs["Clearcoat"].default_value = float(coat)
    return mat


def floor_material(rng, base, lines, tiles):
    """Principled floor: noise stains and grain, optional brick-node tiles, painted cell lines."""
    mat = bpy.data.materials.new("floor")
    mat.use_nodes = True
    nt = mat.node_tree
    nodes, links = nt.nodes, nt.links
    bsdf = nodes["Principled BSDF"]
    coord = nodes.new("ShaderNodeTexCoord")
    base = np.array(base)

    stain = nodes.new("ShaderNodeTexNoise")
    stain.inputs["Scale"].default_value = float(rng.uniform(0.08, 0.3))
    stain.inputs["Detail"].default_value = 3.0
    links.new(coord.outputs["Object"], stain.inputs["Vector"])
    ramp = nodes.new("ShaderNodeValToRGB")
    amp = rng.uniform(0.05, 0.14)
    ramp.color_ramp.elements[0].color = (*(base * (1 - amp)), 1)
    ramp.color_ramp.elements[1].color = (*np.clip(base * (1 + amp), 0, 1), 1)
    links.new(stain.outputs["Fac"], ramp.inputs["Fac"])
    colour = ramp.outputs["Color"]

    grain = nodes.new("ShaderNodeTexNoise")
    grain.inputs["Scale"].default_value = float(rng.uniform(6, 20))
    grain.inputs["Detail"].default_value = 6.0
    links.new(coord.outputs["Object"], grain.inputs["Vector"])
    mix = nodes.new("ShaderNodeMixRGB")
    mix.blend_type = "OVERLAY"
    mix.inputs["Fac"].default_value = float(rng.uniform(0.05, 0.2))
    links.new(colour, mix.inputs["Color1"])
    links.new(grain.outputs["Color"], mix.inputs["Color2"])
    colour = mix.outputs["Color"]

    if tiles:
        brick = nodes.new("ShaderNodeTexBrick")
        brick.offset = tiles["offset"]
        brick.inputs["Scale"].default_value = 1.0
        brick.inputs["Brick Width"].default_value = tiles["size"]
        brick.inputs["Row Height"].default_value = tiles["size"]
        brick.inputs["Mortar Size"].default_value = tiles["mortar"]
        brick.inputs["Mortar Smooth"].default_value = 0.2
        brick.inputs["Bias"].default_value = 0.0
        brick.inputs["Color1"].default_value = (1, 1, 1, 1)
        brick.inputs["Color2"].default_value = (*([1 - tiles["contrast"]] * 3), 1)
        brick.inputs["Mortar"].default_value = (*([1 - 2.5 * tiles["contrast"] - 0.08] * 3), 1)
        links.new(coord.outputs["Object"], brick.inputs["Vector"])
        mul = nodes.new("ShaderNodeMixRGB")
        mul.blend_type = "MULTIPLY"
        mul.inputs["Fac"].default_value = 1.0
        links.new(colour, mul.inputs["Color1"])
        links.new(brick.outputs["Color"], mul.inputs["Color2"])
        colour = mul.outputs["Color"]

    if lines:
        sep = nodes.new("ShaderNodeSeparateXYZ")
        links.new(coord.outputs["Object"], sep.inputs["Vector"])
        masks = []
        for axis in ("X", "Y"):
            add = nodes.new("ShaderNodeMath")
            add.operation = "ADD"
            add.inputs[1].default_value = lines["width"] / 2
            links.new(sep.outputs[axis], add.inputs[0])
            fr = nodes.new("ShaderNodeMath")
            fr.operation = "FRACT"
            links.new(add.outputs[0], fr.inputs[0])
            lt = nodes.new("ShaderNodeMath")
            lt.operation = "LESS_THAN"
            lt.inputs[1].default_value = lines["width"]
            links.new(fr.outputs[0], lt.inputs[0])
            masks.append(lt)
        mx = nodes.new("ShaderNodeMath")
        mx.operation = "MAXIMUM"
        links.new(masks[0].outputs[0], mx.inputs[0])
        links.new(masks[1].outputs[0], mx.inputs[1])
        paint = nodes.new("ShaderNodeMixRGB")
        links.new(mx.outputs[0], paint.inputs["Fac"])
        links.new(colour, paint.inputs["Color1"])
        paint.inputs["Color2"].default_value = (*lines["colour"], 1)
        colour = paint.outputs["Color"]

    links.new(colour, bsdf.inputs["Base Color"])
    rough = nodes.new("ShaderNodeMapRange")
    r0 = rng.uniform(0.22, 0.45) if rng.random() < 0.3 else rng.uniform(0.55, 0.85)
    rough.inputs["To Min"].default_value = float(r0)
    rough.inputs["To Max"].default_value = float(min(1.0, r0 + 0.2))
    links.new(stain.outputs["Fac"], rough.inputs["Value"])
    links.new(rough.outputs["Result"], bsdf.inputs["Roughness"])
    bump = nodes.new("ShaderNodeBump")
    bump.inputs["Strength"].default_value = float(rng.uniform(0.02, 0.15))
    bump.inputs["Distance"].default_value = 0.01
    links.new(grain.outputs["Fac"], bump.inputs["Height"])
    links.new(bump.outputs["Normal"], bsdf.inputs["Normal"])
    return mat, r0


# ---------------------------------------------------------------- objects

def link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


def mesh_object(name, verts, faces, mat, smooth=False):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], faces)
    me.update()
    if smooth:
        for p in me.polygons:
            p.use_smooth = True
    me.materials.append(mat)
    return link(bpy.data.objects.new(name, me))


def prism(name, cx, cy, z0, z1, outline, mat, smooth=False):
    """A vertical prism over a closed outline (list of (x, y) offsets, counter-clockwise)."""
    n = len(outline)
    verts = [(cx + x, cy + y, z0) for x, y in outline] + [(cx + x, cy + y, z1) for x, y in outline]
    faces = [list(range(n - 1, -1, -1)), list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    obj = mesh_object(name, verts, faces, mat)
    if smooth:
        for p in obj.data.polygons[2:]:
            p.use_smooth = True
    return obj


def circle(r, n, phase=0.0, rx=None):
    rx = r if rx is None else rx
    return [(rx * math.cos(phase + 2 * math.pi * i / n), r * math.sin(phase + 2 * math.pi * i / n)) for i in range(n)]


def rotate(outline, yaw):
    c, s = math.cos(yaw), math.sin(yaw)
    return [(c * x - s * y, s * x + c * y) for x, y in outline]


def flat_polygon(name, cx, cy, z, outline, mat):
    """A thin painted mark: a prism 1.5 mm high over a star-shaped outline (fan from its centre)."""
    n = len(outline)
    verts = [(cx, cy, z)] + [(cx + x, cy + y, z) for x, y in outline]
    verts += [(cx, cy, 0.0005)] + [(cx + x, cy + y, 0.0005) for x, y in outline]
    faces = [[0, 1 + i, 1 + (i + 1) % n] for i in range(n)]
    b = n + 1
    faces += [[b, b + 1 + (i + 1) % n, b + 1 + i] for i in range(n)]
    faces += [[1 + i, b + 1 + i, b + 1 + (i + 1) % n, 1 + (i + 1) % n] for i in range(n)]
    return mesh_object(name, verts, faces, mat)


def annulus(name, cx, cy, z, r_out, r_in, mat, n=48):
    verts = []
    for i in range(n):
        a = 2 * math.pi * i / n
        verts += [(cx + r_out * math.cos(a), cy + r_out * math.sin(a), z), (cx + r_in * math.cos(a), cy + r_in * math.sin(a), z)]
    faces = [[2 * i, 2 * ((i + 1) % n), 2 * ((i + 1) % n) + 1, 2 * i + 1] for i in range(n)]
    return mesh_object(name, verts, faces, mat)


def uv_sphere(name, centre, r, mat, scale=(1, 1, 1)):
    me = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=24, v_segments=12, radius=r)
    bm.to_mesh(me)
    bm.free()
    for p in me.polygons:
        p.use_smooth = True
    me.materials.append(mat)
    obj = link(bpy.data.objects.new(name, me))
    obj.location = centre
    obj.scale = scale
    return obj


def make_robot(i, rng, robot, cx, cy):
    col = np.clip(np.array(robot["colour"]) * rng.uniform(0.85, 1.1), 0, 1)
    mat = principled(f"robot{i}", col, robot["rough"], spec=0.5, coat=robot["coat"])
    r, hgt, shape = robot["size"] / 2, robot["height"], robot["shape"]
    yaw = float(rng.uniform(0, 2 * math.pi))
    if shape == "hex":
        prism(f"robot{i}", cx, cy, 0, hgt, circle(r, 6, yaw), mat)
    elif shape == "frustum":
        n = 32
        bot, top = circle(r, n), circle(0.62 * r, n)
        verts = [(cx + x, cy + y, 0) for x, y in bot] + [(cx + x, cy + y, hgt) for x, y in top]
        faces = [list(range(n - 1, -1, -1)), list(range(n, 2 * n))] + [[k, (k + 1) % n, n + (k + 1) % n, n + k] for k in range(n)]
        obj = mesh_object(f"robot{i}", verts, faces, mat)
        for p in obj.data.polygons[2:]:
            p.use_smooth = True
    elif shape == "roundbox":
        side = r * math.sqrt(math.pi) / 2
        obj = prism(f"robot{i}", cx, cy, 0, hgt, rotate([(-side, -side), (side, -side), (side, side), (-side, side)], yaw), mat)
        mod = obj.modifiers.new("bevel", "BEVEL")
        mod.width = 0.3 * min(side, hgt / 2)
        mod.segments = 3
    elif shape == "capsule":
        # Lying along `yaw`: a cylinder of radius r / 2 between two spheres; footprint 2 r by r.
        rr = 0.5 * r
        half = r - rr
        dx, dy = math.cos(yaw) * half, math.sin(yaw) * half
        for k, sgn in enumerate((-1, 1)):
            uv_sphere(f"robot{i}e{k}", (cx + sgn * dx, cy + sgn * dy, rr), rr, mat)
        me = bpy.data.meshes.new(f"robot{i}")
        bm = bmesh.new()
        bmesh.ops.create_cone(bm, cap_ends=False, segments=24, radius1=rr, radius2=rr, depth=2 * half)
        bm.to_mesh(me)
        bm.free()
        for p in me.polygons:
            p.use_smooth = True
        me.materials.append(mat)
        obj = link(bpy.data.objects.new(f"robot{i}", me))
        obj.location = (cx, cy, rr)
        obj.rotation_euler = (0.0, math.pi / 2, yaw)
    else:  # lidar: a cylinder with a dark lidar puck on top
        prism(f"robot{i}", cx, cy, 0, hgt, circle(r, 32), mat, smooth=True)
        dark = principled(f"lidar{i}", (0.03, 0.03, 0.035), 0.3)
        prism(f"robot{i}l", cx, cy, hgt, hgt + 0.12, circle(0.32 * r, 24), dark, smooth=True)


def make_goal(i, rng, goal, cx, cy):
    col = np.clip(np.array(goal["colour"]) * rng.uniform(0.9, 1.1), 0, 1)
    mat = principled(f"goal{i}", col, rng.uniform(0.4, 0.8))
    r, shape, z = goal["size"] / 2, goal["shape"], 0.002
    yaw = float(rng.uniform(0, 2 * math.pi))
    if shape == "ring":
        annulus(f"goal{i}", cx, cy, z, r, r * goal["inner"], mat)
    elif shape == "star":
        pts = []
        for k in range(10):
            rad = r if k % 2 == 0 else r * goal["inner"]
            a = yaw + math.pi * k / 5
            pts.append((rad * math.cos(a), rad * math.sin(a)))
        flat_polygon(f"goal{i}", cx, cy, z, pts, mat)
    elif shape == "xcross":
        t = goal["inner"] * r  # half the arm's width
        arm = [(-r, -t), (r, -t), (r, t), (-r, t)]
        for k, ang in enumerate((math.pi / 4, -math.pi / 4)):
            flat_polygon(f"goal{i}a{k}", cx, cy, z + 0.0003 * k, rotate(arm, yaw * 0.1 + ang), mat)
    elif shape == "target":
        flat_polygon(f"goal{i}", cx, cy, z, circle(r, 40), mat)
        white = principled(f"goal{i}w", (0.8, 0.8, 0.78), 0.6)
        flat_polygon(f"goal{i}c", cx, cy, z + 0.0005, circle(r * goal["inner"], 24), white)
    else:
        flat_polygon(f"goal{i}", cx, cy, z, circle(r, 40), mat)


def make_shelf(i, rng, fam, s, h, inset):
    x0, x1 = s["x"] + inset, s["x"] + s["w"] - inset
    y1, y0 = h - s["y"] - inset, h - s["y"] - s["h"] + inset
    hgt = s["height"]
    mat = principled(f"shelf{i}", s["colour"], s.get("rough", 0.45), metallic=s.get("metal", 0.0))
    outline = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    obj = prism(f"shelf{i}", 0, 0, 0, hgt, outline, mat)
    obj["shelf"] = True
    if s["goods"]:
        # Cartons on the top, one per cell, each a little smaller than the cell.
        box = principled(f"goods{i}", np.clip(np.array(fam["goods_colour"]) * rng.uniform(0.8, 1.15), 0, 1), 0.8)
        for cx in range(s["w"]):
            for cy in range(s["h"]):
                m = rng.uniform(0.08, 0.16)
                gx0, gy0 = s["x"] + cx + m, h - s["y"] - cy - 1 + m
                gh = rng.uniform(0.1, 0.35)
                o = prism(f"goods{i}_{cx}_{cy}", 0, 0, hgt, hgt + gh,
                          [(gx0, gy0), (gx0 + 1 - 2 * m, gy0), (gx0 + 1 - 2 * m, gy0 + 1 - 2 * m), (gx0, gy0 + 1 - 2 * m)], box)
                o["shelf"] = True


# ---------------------------------------------------------------- light

def setup_world(rng, light):
    world = bpy.data.worlds.new("world")
    bpy.context.scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    bg = nt.nodes["Background"]
    if light["kind"] == "sun":
        sky = nt.nodes.new("ShaderNodeTexSky")
        sky.sky_type = "NISHITA"
        sky.sun_disc = False
        sky.sun_elevation = math.radians(light["elevation"])
        sky.sun_rotation = math.radians(light["azimuth"])
        sky.air_density = float(rng.uniform(0.5, 2.0))
        sky.dust_density = float(rng.uniform(0.0, 3.0))
        nt.links.new(sky.outputs["Color"], bg.inputs["Color"])
        bg.inputs["Strength"].default_value = light["sky"]
        sun = bpy.data.lights.new("sun", "SUN")
        sun.energy = light["sun"]
        sun.angle = math.radians(light["angle"])
        sun.color = light["colour"]
        obj = link(bpy.data.objects.new("sun", sun))
        el, az = math.radians(light["elevation"]), math.radians(light["azimuth"])
        d = Vector((math.cos(el) * math.sin(az), -math.cos(el) * math.cos(az), math.sin(el)))
        obj.rotation_euler = d.to_track_quat("Z", "Y").to_euler()
    else:
        bg.inputs["Color"].default_value = (*light["ambient_colour"], 1)
        bg.inputs["Strength"].default_value = light["sky"]
        for k, (x, y, z, size, power) in enumerate(light["lamps"]):
            lamp = bpy.data.lights.new(f"lamp{k}", "AREA")
            lamp.shape = "DISK" if k % 2 else "RECTANGLE"
            lamp.size = size
            lamp.size_y = size * 0.5
            lamp.energy = power
            lamp.color = light["colour"]
            obj = link(bpy.data.objects.new(f"lamp{k}", lamp))
            obj.location = (x, y, z)
            obj.visible_camera = False


# ---------------------------------------------------------------- image

def blur(img, sigma):
    if sigma <= 0:
        return img
    rad = max(1, int(3 * sigma))
    k = np.exp(-0.5 * (np.arange(-rad, rad + 1) / sigma) ** 2)
    k /= k.sum()
    pad = np.pad(img, ((rad, rad), (rad, rad), (0, 0)), mode="edge")
    tmp = sum(k[i] * pad[:, i:i + img.shape[1]] for i in range(len(k)))
    return sum(k[i] * tmp[i:i + img.shape[0]] for i in range(len(k)))


def develop(rng, lin, floor_mask, exposure):
    """Linear render -> 8-bit sRGB: exposure from the floor's median, white balance, a tone
    curve (clipped, or a soft shoulder), vignetting."""
    lum = lin @ np.array([0.2126, 0.7152, 0.0722])
    ref = np.median(lum[floor_mask]) if floor_mask.any() else np.median(lum)
    target = rng.uniform(*exposure)
    img = lin * (target / max(ref, 1e-6))
    img = img * np.array([rng.uniform(0.92, 1.08), 1.0, rng.uniform(0.92, 1.08)])
    hh, ww = img.shape[:2]
    yy, xx = np.mgrid[0:hh, 0:ww]
    rr = ((xx - ww / 2) ** 2 + (yy - hh / 2) ** 2) / ((ww / 2) ** 2 + (hh / 2) ** 2)
    vig = rng.uniform(0.0, 0.3)
    img = img * (1 - vig * rr)[:, :, None]
    curve = "shoulder" if rng.random() < 0.5 else "clip"
    if curve == "shoulder":
        white = rng.uniform(1.5, 4.0)
        img = 1.5 * img * (1 + img / white ** 2) / (1 + img)  # extended Reinhard, a little brighter
    img = np.clip(img, 0, 1)
    img = np.where(img <= 0.0031308, 12.92 * img, 1.055 * np.power(img, 1 / 2.4) - 0.055)
    return img, dict(exposure_target=target, vignette=vig, curve=curve)


# ---------------------------------------------------------------- scene

def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def render_one(args, seed, out_dir):
    fam = FAMILIES[args.family]
    rng = np.random.default_rng([ord(args.family), 7, seed])
    if args.cells:
        w, h = parse_range(args.cells.replace("x", "-"))
    else:
        w, h = int(rng.integers(10, 33)), int(rng.integers(8, 25))
    cell_px = float(rng.uniform(*parse_range(args.cell_px, float)))
    n_lo, n_hi = parse_range(args.robots)
    n = int(rng.integers(n_lo, n_hi + 1))
    big = rng.random() < 0.15
    robot = dict(shape=fam["robot_shapes"][int(rng.integers(len(fam["robot_shapes"])))],
                 size=float(rng.uniform(*fam.get("big_robot_size", (1.3, 1.7))) if big
                            else rng.uniform(*fam.get("robot_size", (0.4, 0.8)))),
                 height=float(rng.uniform(0.15, 0.5)), rough=float(rng.uniform(0.15, 0.6)),
                 coat=float(rng.uniform(0, 0.6)),
                 colour=[rng.uniform(*r) for r in fam.get("robot_rgb", ((0.5, 0.85), (0.02, 0.12), (0.02, 0.1)))])
    goal = dict(shape=fam["goal_shapes"][int(rng.integers(len(fam["goal_shapes"])))],
                size=float(rng.uniform(*fam.get("goal_size", (0.4, 0.8)))), inner=float(rng.uniform(0.35, 0.55)),
                colour=[rng.uniform(*r) for r in fam.get("goal_rgb", ((0.03, 0.15), (0.35, 0.65), (0.05, 0.2)))])
    # Smallest marks: a robot 4 px wide, a goal's thin parts at least about 2 px.
    robot["size"] = max(robot["size"], (8.0 if robot["shape"] == "capsule" else 4.0) / cell_px)
    thin = {"ring": 1 - goal["inner"], "star": 0.6, "xcross": goal["inner"], "target": 1 - goal["inner"], "disc": 1.0}
    goal["size"] = max(goal["size"], 4.0 / cell_px, 2.5 / cell_px / thin[goal["shape"]])
    goal["size"] = min(goal["size"], 0.9)
    reach_r = robot["size"] / 2 + 0.1
    reach_g = goal["size"] / 2 + 0.08
    blocked, shelves, robots, goals = pick_layout(rng, w, h, n, fam, reach_r, reach_g)
    for s in shelves:
        s["rough"] = float(rng.uniform(0.25, 0.7))
        s["metal"] = float(rng.uniform(0, 0.5)) if rng.random() < 0.3 else 0.0
    inset = float(rng.uniform(*fam["shelf_inset"]))

    base = fam["floors"][int(rng.integers(len(fam["floors"])))]
    lines = None
    if rng.random() < args.lines:
        u = rng.random()
        lines = dict(width=float(rng.uniform(0.03, 0.08)),
                     colour=[0.08, 0.08, 0.08] if u < 0.45 else ([0.85, 0.85, 0.82] if u < 0.85 else [0.8, 0.62, 0.04]))
    tiles = None
    if rng.random() < 0.5:
        tiles = dict(size=float(rng.choice([0.25, 1 / 3, 0.5, 0.8, 1.0, 1.25])), offset=float(rng.choice([0.0, 0.5])),
                     mortar=float(rng.uniform(0.006, 0.02)), contrast=float(rng.uniform(0.02, 0.08)))

    straight = rng.random() < 0.4 or args.tilt == 0
    cam = plan_camera(rng, w, h, cell_px, dict(fam, tilt_max=args.tilt or fam["tilt_max"]), straight)

    if rng.random() < 0.55:
        el = float(rng.uniform(*fam.get("sun_elevation", (25, 80))))
        warm = rng.uniform(-0.15, 0.15)
        light = dict(kind="sun", elevation=el, azimuth=float(rng.uniform(0, 360)), sun=float(rng.uniform(2.5, 6.0)),
                     angle=float(rng.uniform(*fam.get("sun_angle", (0.5, 12.0)))), sky=float(rng.uniform(0.15, 0.6)),
                     colour=[1 + warm, 1.0, 1 - warm])
    else:
        warm = rng.uniform(-0.1, 0.1)
        lamps = []
        k = int(rng.integers(3, 9))
        ceiling = float(rng.uniform(0.25, 0.6)) * max(w, h) + max([s["height"] for s in shelves] + [0.0])
        for _ in range(k):
            lamps.append((float(rng.uniform(0.1, 0.9) * w), float(rng.uniform(0.1, 0.9) * h), ceiling + float(rng.uniform(0, 1.5)),
                          float(rng.uniform(1.5, 5.0)), float(rng.uniform(0.5, 1.5)) * ceiling ** 2 * 20))
        light = dict(kind="area", lamps=lamps, sky=float(rng.uniform(0.2, 0.8)),
                     ambient_colour=[0.8 - warm, 0.85, 0.9 + warm], colour=[1 + warm, 1.0, 1 - warm])

    # ---- build
    reset()
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.spp
    scene.cycles.use_adaptive_sampling = True
    scene.cycles.adaptive_threshold = 0.02
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 4
    scene.cycles.seed = seed
    scene.cycles.filter_width = float(rng.uniform(1.0, 2.0))
    scene.render.threads_mode = "FIXED"
    scene.render.threads = args.threads
    scene.render.resolution_x, scene.render.resolution_y = cam["size"]
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"

    cam_data = bpy.data.cameras.new("camera")
    cam_data.sensor_fit = "HORIZONTAL"
    cam_data.angle_x = cam["fov"]
    cam_data.clip_start = 0.1
    cam_data.clip_end = 10000
    cam_obj = link(bpy.data.objects.new("camera", cam_data))
    cam_obj.matrix_world = cam["matrix"]
    scene.camera = cam_obj

    floor_mat, floor_rough = floor_material(rng, base, lines, tiles)
    mesh_object("floor", [(0, 0, 0), (w, 0, 0), (w, h, 0), (0, h, 0)], [[0, 1, 2, 3]], floor_mat)
    surround = principled("surround", np.clip(np.array(base) * rng.uniform(0.6, 1.2), 0, 1), 0.8)
    big_r = 4 * max(w, h)
    mesh_object("surround", [(-big_r, -big_r, -0.002), (w + big_r, -big_r, -0.002), (w + big_r, h + big_r, -0.002),
                             (-big_r, h + big_r, -0.002)], [[0, 1, 2, 3]], surround)
    for i, s in enumerate(shelves):
        make_shelf(i, rng, fam, s, h, inset)
    setup_world(rng, light)

    # Drop the marks a shelf hides from the camera (their centre on the floor, and a robot's top).
    bpy.context.view_layer.update()
    dg = bpy.context.evaluated_depsgraph_get()
    eye = cam["matrix"].to_translation()

    def hidden(cx, cy, z):
        p = Vector((cx, h - cy, z))
        d = p - eye
        hit, loc, _n, _i, obj, _m = scene.ray_cast(dg, eye, d.normalized(), distance=d.length - 1e-3)
        return bool(hit and obj.get("shelf"))

    seen_goals = [g for g in goals if not hidden(g[0], g[1], 0.003)]
    seen_robots = [r for r in robots if not hidden(r[0], r[1], 0.01) and not hidden(r[0], r[1], robot["height"])]
    n = min(len(seen_robots), len(seen_goals))
    dropped = dict(robots=len(robots) - len(seen_robots), goals=len(goals) - len(seen_goals))
    robots, goals = seen_robots[:n], seen_goals[:n]
    for i, (cx, cy) in enumerate(robots):
        make_robot(i, rng, robot, cx, h - cy)
    for i, (cx, cy) in enumerate(goals):
        make_goal(i, rng, goal, cx, h - cy)

    with tempfile.TemporaryDirectory() as tmp:
        exr = os.path.join(tmp, "render.exr")
        scene.render.filepath = exr
        bpy.ops.render.render(write_still=True)
        im = bpy.data.images.load(exr)
        ww, hh = im.size
        buf = np.empty(ww * hh * 4, np.float32)
        im.pixels.foreach_get(buf)
        lin = buf.reshape(hh, ww, 4)[::-1, :, :3].astype(np.float64)  # Blender's rows run bottom-up

    # ---- truth: the floor's corners through Blender's own camera
    corners = []
    for x, y in ((0, h), (w, h), (w, 0), (0, 0)):
        v = world_to_camera_view(scene, cam_obj, Vector((x, y, 0.0)))
        corners.append((v.x * ww, (1 - v.y) * hh))
    # The floor in the image (for exposure): inside the corner quadrilateral.
    yy, xx = np.mgrid[0:hh, 0:ww] + 0.5
    inside = np.ones((hh, ww), bool)
    for k in range(4):
        (ax, ay), (bx, by) = corners[k], corners[(k + 1) % 4]
        inside &= (bx - ax) * (yy - ay) - (by - ay) * (xx - ax) >= 0
    img, dev = develop(rng, lin, inside, fam.get("exposure", (0.16, 0.32)))
    sigma = float(rng.uniform(0, fam.get("blur_max", 1.1)))
    img = blur(img, sigma)
    noise = float(rng.uniform(0, fam.get("noise_max", 0.025)))
    img = np.clip(img + rng.normal(0, noise, img.shape), 0, 1)
    pixels = Image.fromarray((img * 255 + 0.5).astype(np.uint8))
    name = f"{args.family}{seed:04d}"
    quality = int(rng.integers(*fam.get("jpeg_quality", (60, 96)))) if rng.random() < args.jpeg else None
    if quality:
        path = os.path.join(out_dir, name + ".jpg")
        pixels.save(path, quality=quality)
    else:
        path = os.path.join(out_dir, name + ".png")
        pixels.save(path, optimize=True)
    truth = {
        "image": os.path.basename(path),
        "renderer": f"blender {bpy.app.version_string} cycles CPU, {args.spp} spp (adaptive), no denoiser",
        "family": args.family, "seed": seed,
        "grid": [w, h],
        "corners": [[round(x, 2), round(y, 2)] for x, y in corners],
        "straight_down": cam["tilt"] == 0,
        "cell_px": cell_px,
        "blocked": [[int(x), int(y)] for y, x in zip(*np.nonzero(blocked))],
        "robots": [[int(cx), int(cy)] for cx, cy in robots],
        "goals": [[int(cx), int(cy)] for cx, cy in goals],
        "robot_centres": [[round(cx, 3), round(cy, 3)] for cx, cy in robots],
        "goal_centres": [[round(cx, 3), round(cy, 3)] for cx, cy in goals],
        "params": {"robot": robot, "goal": goal, "lines": lines, "tiles": tiles, "floor": list(base),
                   "floor_roughness": floor_rough, "shelves": shelves, "shelf_inset": inset, "light": light,
                   "tilt_deg": cam["tilt"], "roll_deg": cam["roll"], "camera_height": cam["height"],
                   "fov_x_deg": math.degrees(cam["fov"]), "hidden_dropped": dropped,
                   "jpeg_quality": quality, "noise": noise, "blur": sigma, "develop": dev,
                   "image_size": [ww, hh]},
    }
    with open(os.path.join(out_dir, name + ".json"), "w") as f:
        json.dump(truth, f, indent=1)
    return path


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="blender -b --factory-startup -noaudio -P render_blender.py --",
                                 description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--family", default="G", choices=sorted(FAMILIES))
    ap.add_argument("--seeds", default="0-9")
    ap.add_argument("--cells", help="WxH (default: random 10-32 x 8-24)")
    ap.add_argument("--cell-px", default="8-40", help="pixels per cell, a range")
    ap.add_argument("--robots", default="4-60")
    ap.add_argument("--tilt", type=float, default=None, help="largest camera tilt in degrees (0: all straight down)")
    ap.add_argument("--lines", type=float, default=0.4, help="share of floors with painted grid lines")
    ap.add_argument("--jpeg", type=float, default=0.5, help="share of images saved as JPEG")
    ap.add_argument("--spp", type=int, default=16, help="Cycles samples per pixel (adaptive)")
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    lo, hi = parse_range(args.seeds)
    for seed in range(lo, hi + 1):
        t0 = time.time()
        path = render_one(args, seed, args.out)
        print(f"RENDERED {path} {time.time() - t0:.1f} s", flush=True)


if __name__ == "__main__":
    main()
