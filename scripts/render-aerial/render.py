"""Renders aerial views of a robot floor with Mitsuba 3 (a physically based ray tracer) and
writes each image with its ground truth (grid, blocked cells, robots, goals, floor corners).

    python render.py OUT_DIR --family A --seeds 0-99 [--cells 24x16] [--robots 4-30]

A scene is a floor of W x H cells (1 world unit per cell) at z = 0 (z up), seen by a pinhole
camera. Cell (x, y) (column x, row y, row 0 at the top of a straight-down view) covers world
[x, x+1] x [H-y-1, H-y]: rows run along -y, as a camera looking down on a right-handed world
with x to the right sees them. Everything random comes from the seed and the family, so a scene is
rebuilt bit for bit by the same command.
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from PIL import Image

import mitsuba as mi

FAMILIES = {
    # A: the tuning family. Cylinder and box robots, disc and square goals, concrete floors.
    "A": dict(robot_shapes=("cylinder", "box"), goal_shapes=("disc", "square"),
              floors=((0.62, 0.62, 0.60), (0.70, 0.66, 0.58), (0.55, 0.57, 0.60)),
              shelf_colours=((0.10, 0.22, 0.60), (0.80, 0.72, 0.12), (0.10, 0.45, 0.50))),
    # B: held out (rendered after the reader was written). Capsule-like robots (cylinder with
    # a dome), ring goals, darker floors, purple and light-blue shelves.
    "B": dict(robot_shapes=("dome", "cylinder"), goal_shapes=("ring", "disc"),
              floors=((0.45, 0.45, 0.47), (0.75, 0.74, 0.70), (0.58, 0.52, 0.46)),
              shelf_colours=((0.35, 0.15, 0.55), (0.30, 0.55, 0.85), (0.12, 0.35, 0.25))),
    # C: held out (rendered after the reader of issue #29 was finished). Yawed-box and puck
    # robots (a cylinder with a darker cap), cross and diamond goals, tiled floors (bluish,
    # beige, asphalt), shelves inset 0.06 cell from their cells' borders in other colours,
    # warmer and cooler light, and a camera from 40 to 180 (not 60 to 140) cells per 24 high.
    "C": dict(robot_shapes=("rotbox", "puck"), goal_shapes=("cross", "diamond"),
              floors=((0.50, 0.55, 0.62), (0.80, 0.72, 0.56), (0.36, 0.36, 0.37)),
              shelf_colours=((0.20, 0.25, 0.75), (0.85, 0.62, 0.10), (0.10, 0.55, 0.70), (0.60, 0.20, 0.65)),
              tiles=0.5, shelf_inset=0.06, warm=0.25, camera_height=(40, 180)),
    # D: held out (rendered after the last change to the reader of issue #29). Cylinder and
    # yawed-box robots, ring, diamond and square goals, greenish-grey, light and brown floors
    # tiled every third of a cell, deep-blue, violet, yellow and teal shelves inset 0.03 cell,
    # and a camera from 50 to 160 cells per 24 high.
    "D": dict(robot_shapes=("cylinder", "rotbox"), goal_shapes=("ring", "diamond", "square"),
              floors=((0.55, 0.58, 0.52), (0.82, 0.80, 0.78), (0.50, 0.42, 0.35)),
              shelf_colours=((0.05, 0.10, 0.45), (0.40, 0.20, 0.70), (0.90, 0.75, 0.15), (0.05, 0.40, 0.45)),
              tiles=1 / 3, shelf_inset=0.03, warm=0.2, camera_height=(50, 160)),
    # E: held out (rendered after the reader of issue #29's second round was finished, scored
    # once). Dome, yawed-box and box-with-a-dome robots, square, cross and ellipse goals, warm
    # grey, dark slate and light sand floors tiled every quarter cell, orange, navy, olive and
    # lilac shelves from 0.3 to 2.0 high inset 0.04 cell, warmer and cooler light, and a
    # camera from 45 to 170 cells per 24 high.
    "E": dict(robot_shapes=("dome", "rotbox", "boxdome"), goal_shapes=("square", "cross", "ellipse"),
              floors=((0.66, 0.60, 0.55), (0.32, 0.35, 0.40), (0.85, 0.80, 0.68)),
              shelf_colours=((0.90, 0.45, 0.10), (0.08, 0.12, 0.35), (0.45, 0.50, 0.15), (0.55, 0.45, 0.80)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.04, warm=0.3, camera_height=(45, 170)),
    # F: held out (rendered before the floor-consistency check of issue #29's third round was
    # finished, scored once with the final reader). Cylinder, box and dome robots, disc, ring
    # and cross goals, cool grey, tan and dark warm-grey floors tiled every half cell, shelves
    # of colours near the floors' (pale blue-grey, dark tan, sage, cream, dark brown) from 0.3
    # to 1.8 high inset 0.05 cell, a lower sun (20-60 degrees up) of varying strength, warmer
    # and cooler light, and a camera from 45 to 170 cells per 24 high.
    "F": dict(robot_shapes=("cylinder", "box", "dome"), goal_shapes=("disc", "ring", "cross"),
              floors=((0.60, 0.62, 0.66), (0.78, 0.70, 0.60), (0.42, 0.40, 0.36)),
              shelf_colours=((0.72, 0.74, 0.80), (0.60, 0.50, 0.38), (0.55, 0.60, 0.50), (0.88, 0.84, 0.74),
                             (0.28, 0.26, 0.23)),
              shelf_height=(0.3, 1.8), tiles=0.5, shelf_inset=0.05, warm=0.3, camera_height=(45, 170),
              sun_elevation=(20, 60), sun_power=(2.2, 3.6)),
    # K: held out from the eighth round of issue #29 (rendered after its reader was finished,
    # scored once). Puck, box-with-a-dome and box robots, ellipse, ring and diamond goals,
    # green-grey, pale warm and dark blue-grey floors tiled every fifth of a cell, pale lilac,
    # cardboard tan, steel blue-grey, petrol and mustard shelves from 0.4 to 2.2 high inset
    # 0.08 cell, a sun 30-75 degrees up of strength 2.5-4.0, warmer and cooler light, and a
    # camera from 40 to 150 cells per 24 high.
    "K": dict(robot_shapes=("puck", "boxdome", "box"), goal_shapes=("ellipse", "ring", "diamond"),
              floors=((0.48, 0.52, 0.50), (0.76, 0.74, 0.68), (0.30, 0.33, 0.38)),
              shelf_colours=((0.70, 0.62, 0.80), (0.72, 0.58, 0.40), (0.42, 0.50, 0.62), (0.05, 0.30, 0.35),
                             (0.75, 0.60, 0.15)),
              shelf_height=(0.4, 2.2), tiles=0.2, shelf_inset=0.08, warm=0.35, camera_height=(40, 150),
              sun_elevation=(30, 75), sun_power=(2.5, 4.0)),
    # L: held out from the ninth round of issue #29 (pale obstacles, shadows against the light
    # around them; rendered after its reader was finished, scored once). Yawed-box, dome and
    # puck robots, ring, square and cross goals, warm mid-grey, slate and light cool-grey
    # floors tiled every quarter cell, cream, plum, navy, light steel and dark brown shelves
    # from 0.3 to 2.0 high inset 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8,
    # warmer and cooler light, and a camera from 45 to 160 cells per 24 high.
    "L": dict(robot_shapes=("rotbox", "dome", "puck"), goal_shapes=("ring", "square", "cross"),
              floors=((0.58, 0.56, 0.52), (0.40, 0.44, 0.46), (0.70, 0.70, 0.72)),
              shelf_colours=((0.85, 0.80, 0.65), (0.55, 0.30, 0.60), (0.20, 0.30, 0.55), (0.65, 0.68, 0.70),
                             (0.35, 0.25, 0.15)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 160),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # M: held out from the ninth round of issue #29, rendered after its last change to the reader
    # (after L was scored) and scored once. Box, box-with-a-dome and cylinder robots, diamond,
    # ellipse and disc goals, warm light, dark green-grey and cool blue-grey floors tiled every
    # third of a cell, off-white, forest green, ochre, slate violet and sage-grey shelves from
    # 0.3 to 1.9 high inset 0.06 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and
    # cooler light, and a camera from 40 to 170 cells per 24 high.
    "M": dict(robot_shapes=("box", "boxdome", "cylinder"), goal_shapes=("diamond", "ellipse", "disc"),
              floors=((0.64, 0.62, 0.56), (0.36, 0.38, 0.36), (0.52, 0.56, 0.62)),
              shelf_colours=((0.80, 0.78, 0.74), (0.25, 0.45, 0.25), (0.70, 0.45, 0.20), (0.30, 0.30, 0.45),
                             (0.60, 0.62, 0.55)),
              shelf_height=(0.3, 1.9), tiles=1 / 3, shelf_inset=0.06, warm=0.25, camera_height=(40, 170),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # N: held out from the ninth round of issue #29, rendered after its last change to the reader
    # (the lean fit's misfit, after M was scored) and scored once. Puck, yawed-box and cylinder
    # robots, cross, ring and ellipse goals, neutral mid-grey, light warm and dark cool floors
    # tiled every half cell, pale grey, magenta-purple, teal-blue, tan and charcoal shelves from
    # 0.3 to 2.1 high inset 0.07 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and
    # cooler light, and a camera from 45 to 165 cells per 24 high.
    "N": dict(robot_shapes=("puck", "rotbox", "cylinder"), goal_shapes=("cross", "ring", "ellipse"),
              floors=((0.50, 0.50, 0.48), (0.70, 0.64, 0.56), (0.30, 0.32, 0.36)),
              shelf_colours=((0.82, 0.82, 0.78), (0.60, 0.20, 0.55), (0.15, 0.40, 0.55), (0.75, 0.60, 0.30),
                             (0.20, 0.20, 0.22)),
              shelf_height=(0.3, 2.1), tiles=0.5, shelf_inset=0.07, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # O: held out from the ninth round of issue #29, rendered after its final reader (the two
    # safety checks added after N's two wrong readings) and scored once. Dome, box and puck
    # robots, disc, diamond and square goals, concrete, sand and slate floors tiled every
    # quarter cell, cream, brick-brown, cobalt, olive and light grey shelves from 0.3 to 2.0
    # high inset 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler
    # light, and a camera from 45 to 165 cells per 24 high.
    "O": dict(robot_shapes=("dome", "box", "puck"), goal_shapes=("disc", "diamond", "square"),
              floors=((0.60, 0.60, 0.58), (0.78, 0.72, 0.60), (0.34, 0.37, 0.42)),
              shelf_colours=((0.86, 0.82, 0.70), (0.45, 0.28, 0.20), (0.12, 0.25, 0.65), (0.42, 0.45, 0.18),
                             (0.75, 0.76, 0.76)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # P: held out from the ninth round of issue #29, rendered after its very last change to the
    # reader (pale squares from 1.4 times the lit floor, after O was scored) and scored once.
    # Cylinder, yawed-box and box-with-a-dome robots, ring, cross and diamond goals, pale
    # concrete, brown-grey and blue-slate floors tiled every third of a cell, ivory, rust,
    # royal blue, moss and silver-grey shelves from 0.3 to 2.0 high inset 0.06 cell, a sun 25-70
    # degrees up of strength 2.4-3.8, warmer and cooler light, and a camera from 45 to 165 cells
    # per 24 high.
    "P": dict(robot_shapes=("cylinder", "rotbox", "boxdome"), goal_shapes=("ring", "cross", "diamond"),
              floors=((0.68, 0.67, 0.64), (0.46, 0.42, 0.38), (0.38, 0.42, 0.50)),
              shelf_colours=((0.90, 0.88, 0.80), (0.55, 0.30, 0.18), (0.15, 0.25, 0.70), (0.35, 0.42, 0.20),
                             (0.70, 0.72, 0.74)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # Q: held out from issue #29's tenth round, rendered before its reader was finished but
    # scored once, after its last change. Box, dome and yawed-box robots, square, ellipse and
    # ring goals, light warm-grey, mid blue-grey and dark brown-grey floors tiled every half
    # cell, chocolate, terracotta, pale sand, teal-green and slate-blue shelves from 0.3 to 2.1
    # high inset 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler
    # light, and a camera from 45 to 165 cells per 24 high.
    "Q": dict(robot_shapes=("box", "dome", "rotbox"), goal_shapes=("square", "ellipse", "ring"),
              floors=((0.72, 0.70, 0.66), (0.48, 0.52, 0.58), (0.36, 0.33, 0.30)),
              shelf_colours=((0.40, 0.24, 0.14), (0.70, 0.36, 0.22), (0.84, 0.78, 0.62), (0.12, 0.45, 0.38),
                             (0.28, 0.36, 0.52)),
              shelf_height=(0.3, 2.1), tiles=0.5, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # R: held out from issue #29's eleventh round, rendered after its last change to the reader
    # and scored once. Puck, box-with-a-dome and cylinder robots, diamond, disc and cross goals,
    # pale green-grey, sandstone and dark slate floors tiled every quarter cell, burgundy,
    # mint, steel blue, ochre and warm grey shelves from 0.3 to 1.9 high inset 0.07 cell, a sun
    # 30-70 degrees up of strength 2.5-3.6, warmer and cooler light, and a camera from 50 to 160
    # cells per 24 high.
    "R": dict(robot_shapes=("puck", "boxdome", "cylinder"), goal_shapes=("diamond", "disc", "cross"),
              floors=((0.62, 0.66, 0.62), (0.74, 0.66, 0.54), (0.30, 0.33, 0.36)),
              shelf_colours=((0.45, 0.10, 0.18), (0.62, 0.82, 0.70), (0.30, 0.45, 0.62), (0.72, 0.55, 0.16),
                             (0.52, 0.50, 0.47)),
              shelf_height=(0.3, 1.9), tiles=0.25, shelf_inset=0.07, warm=0.3, camera_height=(50, 160),
              sun_elevation=(30, 70), sun_power=(2.5, 3.6)),
    # S: held out from issue #29's eleventh round, rendered after its very last change to the
    # reader (after R was scored) and scored once. Box, cylinder and yawed-box robots, ring,
    # square and ellipse goals, light concrete, cool mid-grey and warm dark-brown floors tiled
    # every third of a cell, plum, sky blue, khaki, dark teal and pale grey shelves from 0.3 to
    # 2.0 high inset 0.05 cell, a sun 25-65 degrees up of strength 2.4-3.7, warmer and cooler
    # light, and a camera from 45 to 170 cells per 24 high.
    "S": dict(robot_shapes=("box", "cylinder", "rotbox"), goal_shapes=("ring", "square", "ellipse"),
              floors=((0.70, 0.69, 0.66), (0.50, 0.52, 0.55), (0.34, 0.30, 0.27)),
              shelf_colours=((0.40, 0.18, 0.42), (0.45, 0.68, 0.88), (0.68, 0.62, 0.40), (0.08, 0.32, 0.34),
                             (0.80, 0.80, 0.78)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.05, warm=0.3, camera_height=(45, 170),
              sun_elevation=(25, 65), sun_power=(2.4, 3.7)),
    # T: held out from issue #29's eleventh round, rendered after its very last change to the
    # reader (after S had been scored once and the round's reader changed for it) and scored
    # once. Dome, box-with-a-dome and puck robots, cross, disc and diamond goals, blue-grey,
    # beige and dark grey floors tiled every half cell, leaf green, off-white, walnut, indigo
    # and amber shelves from 0.3 to 2.0 high inset 0.06 cell, a sun 25-70 degrees up of
    # strength 2.4-3.8, warmer and cooler light, and a camera from 45 to 165 cells per 24 high.
    "T": dict(robot_shapes=("dome", "boxdome", "puck"), goal_shapes=("cross", "disc", "diamond"),
              floors=((0.58, 0.60, 0.64), (0.76, 0.70, 0.62), (0.40, 0.38, 0.36)),
              shelf_colours=((0.20, 0.50, 0.20), (0.85, 0.85, 0.82), (0.55, 0.35, 0.25), (0.25, 0.25, 0.60),
                             (0.90, 0.60, 0.10)),
              shelf_height=(0.3, 2.0), tiles=0.5, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # U: held out from issue #29's eleventh round, rendered after its very last change to the
    # reader (after T had been scored once and looked at) and scored once. Cylinder, dome and
    # box robots, square, ring and cross goals, warm light grey, green-grey and dark blue-grey
    # floors tiled every quarter cell, rust, pale blue, olive, charcoal and cream shelves from
    # 0.3 to 2.0 high inset 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and
    # cooler light, and a camera from 45 to 165 cells per 24 high.
    "U": dict(robot_shapes=("cylinder", "dome", "box"), goal_shapes=("square", "ring", "cross"),
              floors=((0.68, 0.66, 0.62), (0.52, 0.56, 0.50), (0.30, 0.33, 0.40)),
              shelf_colours=((0.60, 0.28, 0.14), (0.62, 0.76, 0.86), (0.45, 0.46, 0.20), (0.22, 0.22, 0.24),
                             (0.88, 0.84, 0.72)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # V: held out from issue #29's eleventh round, rendered after its very last change to the
    # reader (the marks' glow, after U was scored) and scored once. Puck, cylinder and
    # yawed-box robots, disc, ellipse and square goals, pale warm grey, mid grey and dark
    # green-grey floors tiled every third of a cell, navy, sand, brick red-brown, light
    # sage and graphite shelves from 0.3 to 2.0 high inset 0.06 cell, a sun 25-70 degrees up of
    # strength 2.4-3.8, warmer and cooler light, and a camera from 45 to 165 cells per 24 high.
    "V": dict(robot_shapes=("puck", "cylinder", "rotbox"), goal_shapes=("disc", "ellipse", "square"),
              floors=((0.74, 0.71, 0.66), (0.50, 0.50, 0.50), (0.32, 0.36, 0.33)),
              shelf_colours=((0.10, 0.16, 0.42), (0.80, 0.72, 0.52), (0.52, 0.24, 0.18), (0.62, 0.72, 0.60),
                             (0.26, 0.27, 0.29)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # W: held out from issue #29's twelfth round, rendered after its very last change to the
    # reader and scored once. Box-with-a-dome, yawed-box and dome robots, ring, ellipse and
    # diamond goals, light concrete, dark brown-grey and blue-grey floors tiled every fifth of a
    # cell, teal, pale yellow, maroon, slate and lavender shelves from 0.3 to 2.0 high inset
    # 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and a
    # camera from 45 to 165 cells per 24 high.
    "W": dict(robot_shapes=("boxdome", "rotbox", "dome"), goal_shapes=("ring", "ellipse", "diamond"),
              floors=((0.66, 0.66, 0.64), (0.36, 0.33, 0.30), (0.50, 0.54, 0.60)),
              shelf_colours=((0.10, 0.45, 0.45), (0.88, 0.82, 0.50), (0.45, 0.12, 0.16), (0.40, 0.44, 0.50),
                             (0.62, 0.56, 0.76)),
              shelf_height=(0.3, 2.0), tiles=0.2, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # X: held out from issue #29's twelfth round, rendered after its very last change to the
    # reader (one larger mark, after W had been scored) and scored once. Cylinder, puck and
    # box robots, cross, square and disc goals, sand, cool mid-grey and dark olive-grey floors
    # tiled every half cell, orange, steel grey, forest green, light blue and plum shelves from
    # 0.3 to 2.0 high inset 0.06 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and
    # cooler light, and a camera from 45 to 165 cells per 24 high.
    "X": dict(robot_shapes=("cylinder", "puck", "box"), goal_shapes=("cross", "square", "disc"),
              floors=((0.72, 0.66, 0.54), (0.48, 0.50, 0.54), (0.34, 0.35, 0.30)),
              shelf_colours=((0.85, 0.45, 0.12), (0.52, 0.54, 0.56), (0.14, 0.34, 0.16), (0.66, 0.80, 0.90),
                             (0.42, 0.20, 0.40)),
              shelf_height=(0.3, 2.0), tiles=0.5, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # Y: held out from issue #29's thirteenth round, rendered after what was meant as its last
    # change to the reader and scored once, with it and with the round's final reader (which
    # mended the far cell's shadow test after X0037 was read wrongly). Cylinder, dome and yawed-box robots, diamond, disc and ellipse
    # goals, warm beige-grey, dark charcoal-blue and light green-grey floors tiled every quarter
    # cell, dark teal, mustard, cool white, brick and navy shelves from 0.3 to 2.0 high inset
    # 0.07 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and a
    # camera from 45 to 165 cells per 24 high.
    "Y": dict(robot_shapes=("cylinder", "dome", "rotbox"), goal_shapes=("diamond", "disc", "ellipse"),
              floors=((0.62, 0.58, 0.52), (0.20, 0.22, 0.26), (0.60, 0.64, 0.58)),
              shelf_colours=((0.10, 0.30, 0.32), (0.80, 0.65, 0.20), (0.88, 0.90, 0.92), (0.55, 0.22, 0.16),
                             (0.12, 0.16, 0.36)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.07, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # Z: held out from issue #29's thirteenth round, rendered after its final reader and scored
    # once. Puck, box-with-a-dome and cylinder robots, ring, square and cross goals, pale
    # warm-grey, dark slate-green and mid blue-grey floors tiled every third of a cell, rust,
    # light grey, dark violet, sea green and ochre shelves from 0.3 to 2.0 high inset 0.05 cell,
    # a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and a camera from 45
    # to 165 cells per 24 high.
    "Z": dict(robot_shapes=("puck", "boxdome", "cylinder"), goal_shapes=("ring", "square", "cross"),
              floors=((0.70, 0.67, 0.62), (0.22, 0.28, 0.25), (0.45, 0.50, 0.58)),
              shelf_colours=((0.50, 0.22, 0.10), (0.75, 0.76, 0.78), (0.28, 0.16, 0.40), (0.20, 0.50, 0.38),
                             (0.76, 0.58, 0.18)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # a: held out from issue #29's fourteenth round, rendered during it and not looked at until
    # scored once with its final reader. Box, dome and puck robots, disc, diamond and square
    # goals, mid warm concrete, dark blue-grey and light cool grey floors tiled every half cell,
    # olive, pale lilac, dark red-brown, steel blue and orange shelves from 0.3 to 2.0 high
    # inset 0.06 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and
    # a camera from 45 to 165 cells per 24 high.
    "a": dict(robot_shapes=("box", "dome", "puck"), goal_shapes=("disc", "diamond", "square"),
              floors=((0.55, 0.52, 0.48), (0.18, 0.20, 0.24), (0.72, 0.74, 0.76)),
              shelf_colours=((0.45, 0.45, 0.20), (0.70, 0.62, 0.78), (0.35, 0.12, 0.10), (0.30, 0.42, 0.58),
                             (0.85, 0.45, 0.12)),
              shelf_height=(0.3, 2.0), tiles=0.5, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # b: held out from issue #29's fifteenth round, rendered during it and not looked at until
    # scored once with its final reader. Cylinder, box and dome robots, cross, ring and disc
    # goals, pale sand, mid slate and near-black floors tiled every quarter cell, pale grey-blue,
    # cream, plum, forest green and rust shelves from 0.3 to 2.0 high inset 0.05 cell, a sun
    # 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and a camera from 45 to 165
    # cells per 24 high.
    "b": dict(robot_shapes=("cylinder", "box", "dome"), goal_shapes=("cross", "ring", "disc"),
              floors=((0.74, 0.68, 0.56), (0.38, 0.42, 0.46), (0.10, 0.10, 0.11)),
              shelf_colours=((0.66, 0.72, 0.80), (0.86, 0.82, 0.66), (0.40, 0.16, 0.36), (0.14, 0.36, 0.18),
                             (0.62, 0.26, 0.10)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # c: held out from issue #29's sixteenth round, rendered during it and not looked at until
    # scored once with its final reader. Puck, yawed-box and box-with-a-dome robots, square,
    # ellipse and ring goals, mid green-grey, dark brown and warm off-white floors tiled every
    # half cell, teal-blue, sand, dark grey-blue, salmon and moss shelves from 0.3 to 2.0 high
    # inset 0.08 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and
    # a camera from 45 to 165 cells per 24 high.
    "c": dict(robot_shapes=("puck", "rotbox", "boxdome"), goal_shapes=("square", "ellipse", "ring"),
              floors=((0.48, 0.52, 0.46), (0.28, 0.22, 0.18), (0.80, 0.78, 0.74)),
              shelf_colours=((0.12, 0.40, 0.55), (0.78, 0.68, 0.45), (0.22, 0.25, 0.32), (0.85, 0.50, 0.42),
                             (0.35, 0.45, 0.15)),
              shelf_height=(0.3, 2.0), tiles=0.5, shelf_inset=0.08, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # d: held out from issue #29's seventeenth round, rendered during it and not looked at until
    # scored once with its final reader. Dome, puck and box robots, diamond, cross and disc
    # goals, light warm grey, dark blue-grey and ochre floors tiled every third of a cell,
    # brick-brown, pale lilac, dark teal, mustard and slate shelves from 0.3 to 2.2 high inset
    # 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and a
    # camera from 45 to 165 cells per 24 high.
    "d": dict(robot_shapes=("dome", "puck", "box"), goal_shapes=("diamond", "cross", "disc"),
              floors=((0.68, 0.66, 0.62), (0.25, 0.28, 0.33), (0.70, 0.60, 0.42)),
              shelf_colours=((0.50, 0.22, 0.14), (0.72, 0.70, 0.82), (0.08, 0.30, 0.30), (0.75, 0.60, 0.15),
                             (0.40, 0.44, 0.50)),
              shelf_height=(0.3, 2.2), tiles=1 / 3, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # e: held out from issue #29's eighteenth round, rendered after its final reader and not
    # looked at until scored once. Cylinder, dome and yawed-box robots, ellipse, square and ring
    # goals, mid beige-grey, dark charcoal-green and pale blue-grey floors tiled every quarter
    # cell, pale sage green, burgundy, light steel, dark olive and tan shelves from 0.3 to 2.0
    # high inset 0.06 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler
    # light, and a camera from 45 to 165 cells per 24 high.
    "e": dict(robot_shapes=("cylinder", "dome", "rotbox"), goal_shapes=("ellipse", "square", "ring"),
              floors=((0.58, 0.55, 0.50), (0.16, 0.19, 0.17), (0.66, 0.70, 0.76)),
              shelf_colours=((0.62, 0.72, 0.58), (0.42, 0.10, 0.16), (0.70, 0.74, 0.80), (0.30, 0.32, 0.14),
                             (0.72, 0.60, 0.42)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # f: held out, rendered in issue #29's twenty-first round (which changed no reading rule)
    # and not looked at until scored once. Puck, box-dome and box robots, disc, cross and
    # diamond goals, light sand, dark slate-blue and mid warm-grey floors tiled every half
    # cell, navy, pale peach, forest green, light grey-violet and rust shelves from 0.3 to 2.1
    # high inset 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler
    # light, and a camera from 45 to 165 cells per 24 high.
    "f": dict(robot_shapes=("puck", "boxdome", "box"), goal_shapes=("disc", "cross", "diamond"),
              floors=((0.74, 0.68, 0.56), (0.18, 0.21, 0.28), (0.50, 0.47, 0.44)),
              shelf_colours=((0.08, 0.12, 0.35), (0.88, 0.74, 0.62), (0.12, 0.32, 0.16), (0.70, 0.68, 0.78),
                             (0.58, 0.26, 0.12)),
              shelf_height=(0.3, 2.1), tiles=0.5, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # g: held out from issue #29's twenty-first round, rendered after its final reader (the
    # band check of `face::shifted_run`) and not looked at until scored once. Yawed-box,
    # cylinder and dome robots, ring, ellipse and cross goals, pale cream, mid blue-grey and
    # dark brown floors tiled every third of a cell, ivory, plum, teal, khaki and charcoal
    # shelves from 0.3 to 2.2 high inset 0.06 cell, a sun 25-70 degrees up of strength
    # 2.4-3.8, warmer and cooler light, and a camera from 45 to 165 cells per 24 high.
    "g": dict(robot_shapes=("rotbox", "cylinder", "dome"), goal_shapes=("ring", "ellipse", "cross"),
              floors=((0.80, 0.77, 0.68), (0.40, 0.44, 0.50), (0.24, 0.18, 0.14)),
              shelf_colours=((0.90, 0.88, 0.80), (0.42, 0.18, 0.38), (0.08, 0.40, 0.42), (0.62, 0.58, 0.38),
                             (0.20, 0.20, 0.22)),
              shelf_height=(0.3, 2.2), tiles=1 / 3, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # h: held out from issue #29's twenty-second round, rendered after its final reader (the
    # shelves of the floor's colour told by their look and their shadow or hidden lines, in
    # `corroborated`) and not looked at until scored once. Dome, puck and cylinder robots,
    # square, disc and ring goals, warm grey, dark olive-grey and pale blue-grey floors tiled
    # every quarter cell, shelves near the floors' colours (greige, dark olive, pale steel)
    # and mustard and maroon ones, from 0.3 to 2.0 high inset 0.07 cell, a sun 20-65 degrees
    # up of strength 2.2-3.6, warmer and cooler light, and a camera from 45 to 165 cells per
    # 24 high.
    "h": dict(robot_shapes=("dome", "puck", "cylinder"), goal_shapes=("square", "disc", "ring"),
              floors=((0.62, 0.58, 0.52), (0.26, 0.27, 0.22), (0.70, 0.74, 0.80)),
              shelf_colours=((0.66, 0.62, 0.55), (0.30, 0.31, 0.25), (0.74, 0.78, 0.84), (0.80, 0.62, 0.12),
                             (0.40, 0.08, 0.12)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.07, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 65), sun_power=(2.2, 3.6)),
    # i: held out from issue #29's twenty-second round, rendered after its last change (a
    # top's lean no longer crosses a free cell, in `cover::reach`) and not looked at until
    # scored once. Box, yawed-box and puck robots, cross, ellipse and square goals, light
    # grey-green, mid brown-grey and dark blue floors tiled every half cell, pale sand (near
    # the first floor), slate, orange, lilac and dark green shelves from 0.3 to 1.9 high inset
    # 0.05 cell, a sun 25-70 degrees up of strength 2.4-3.8, warmer and cooler light, and a
    # camera from 45 to 165 cells per 24 high.
    "i": dict(robot_shapes=("box", "rotbox", "puck"), goal_shapes=("cross", "ellipse", "square"),
              floors=((0.70, 0.74, 0.66), (0.46, 0.42, 0.38), (0.16, 0.18, 0.30)),
              shelf_colours=((0.76, 0.78, 0.68), (0.30, 0.34, 0.40), (0.90, 0.50, 0.12), (0.66, 0.56, 0.80),
                             (0.10, 0.30, 0.14)),
              shelf_height=(0.3, 1.9), tiles=0.5, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 70), sun_power=(2.4, 3.8)),
    # j: held out from issue #29's twenty-third round, rendered after its final reader (a run's
    # far cell told by the view's other faces, an edge cell and a cell a top may cover almost
    # whole told by their runs' faces) and not looked at until scored once. Box-with-a-dome,
    # cylinder and yawed-box robots, diamond, ring and ellipse goals, cool mid-grey, warm
    # beige and dark green-grey floors tiled every quarter cell, a pale grey-blue shelf near
    # the first floor, a cream one near the second, and teal, brick and navy ones, from 0.3 to
    # 2.1 high inset 0.06 cell, a sun 20-70 degrees up of strength 2.3-3.7, warmer and cooler
    # light, and a camera from 45 to 165 cells per 24 high.
    "j": dict(robot_shapes=("boxdome", "cylinder", "rotbox"), goal_shapes=("diamond", "ring", "ellipse"),
              floors=((0.52, 0.54, 0.58), (0.78, 0.70, 0.58), (0.22, 0.25, 0.22)),
              shelf_colours=((0.60, 0.64, 0.70), (0.86, 0.80, 0.68), (0.10, 0.45, 0.48), (0.58, 0.26, 0.16),
                             (0.10, 0.14, 0.40)),
              shelf_height=(0.3, 2.1), tiles=0.25, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # k: held out from issue #29's twenty-third round, rendered after the edge cells' faces
    # were withdrawn (the round's final reader) and not looked at until scored once. Puck,
    # dome and box robots, square, cross and disc goals, pale warm grey, mid slate and dark
    # brown floors tiled every third of a cell, a light stone shelf near the first floor, a
    # dark chocolate one near the third, and ochre, plum and sea-green ones, from 0.3 to 2.0
    # high inset 0.05 cell, a sun 20-70 degrees up of strength 2.3-3.7, warmer and cooler
    # light, and a camera from 45 to 165 cells per 24 high.
    "k": dict(robot_shapes=("puck", "dome", "box"), goal_shapes=("square", "cross", "disc"),
              floors=((0.74, 0.72, 0.68), (0.36, 0.40, 0.46), (0.30, 0.22, 0.16)),
              shelf_colours=((0.80, 0.78, 0.72), (0.24, 0.16, 0.11), (0.78, 0.58, 0.16), (0.45, 0.20, 0.40),
                             (0.18, 0.50, 0.38)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # l: held out from issue #29's twenty-fourth round, rendered after its first rule (a floor
    # pixel's tint told as the shadows' light) and not looked at until scored once with the
    # round's final reader.
    # Rotated-box, puck and box-with-a-dome robots, ring, square and diamond goals, light
    # blue-grey, mid olive-grey and dark plum-grey floors tiled every half cell, pale sand and
    # dark blue-grey shelves (the latter bluish after white balance, as a shadow under a blue
    # sky is), and rust, moss and violet ones, from 0.3 to 2.0 high inset 0.06 cell, a sun 20-70 degrees up of strength 2.3-3.7, warmer and cooler light, and a camera
    # from 45 to 165 cells per 24 high.
    "l": dict(robot_shapes=("rotbox", "puck", "boxdome"), goal_shapes=("ring", "square", "diamond"),
              floors=((0.66, 0.70, 0.76), (0.44, 0.46, 0.38), (0.26, 0.20, 0.26)),
              shelf_colours=((0.82, 0.76, 0.62), (0.30, 0.34, 0.42), (0.55, 0.24, 0.12), (0.30, 0.42, 0.16),
                             (0.40, 0.22, 0.60)),
              shelf_height=(0.3, 2.0), tiles=0.5, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # m: held out from issue #29's twenty-fourth round, rendered after its final reader (a
    # shelf's own top over its face read as floor, also beside a covered neighbour when the
    # top's band runs across the whole cell) and not looked at until scored once.
    # Box-with-a-dome, cylinder and dome robots, cross, ellipse and disc goals, mid warm grey,
    # pale green-grey and dark navy floors tiled every third of a cell, cream, dark teal,
    # orange, lilac and charcoal shelves, from 0.3 to 2.1 high inset 0.05 cell, a sun 20-70
    # degrees up of strength 2.3-3.7, warmer and cooler light, and a camera from 45 to 165
    # cells per 24 high.
    "m": dict(robot_shapes=("boxdome", "cylinder", "dome"), goal_shapes=("cross", "ellipse", "disc"),
              floors=((0.58, 0.54, 0.50), (0.70, 0.74, 0.68), (0.18, 0.20, 0.28)),
              shelf_colours=((0.86, 0.82, 0.70), (0.10, 0.30, 0.32), (0.85, 0.45, 0.10), (0.66, 0.56, 0.80),
                             (0.22, 0.22, 0.24)),
              shelf_height=(0.3, 2.1), tiles=1 / 3, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # n: held out from issue #29's twenty-fourth round, rendered after its final reader (dark
    # tops of another hue than the shadows', told by their shadow) and not looked at until
    # scored once. Cylinder, rotated-box and puck robots, diamond, square and ring goals, light
    # warm grey, mid blue-grey and dark olive floors tiled every half cell, charcoal-blue, dark
    # brown, pale stone, teal and magenta shelves, from 0.3 to 2.0 high inset 0.06 cell, a sun
    # 20-70 degrees up of strength 2.3-3.7, warmer and cooler light, and a camera from 45 to 165
    # cells per 24 high.
    "n": dict(robot_shapes=("cylinder", "rotbox", "puck"), goal_shapes=("diamond", "square", "ring"),
              floors=((0.72, 0.68, 0.62), (0.46, 0.50, 0.56), (0.28, 0.28, 0.18)),
              shelf_colours=((0.20, 0.24, 0.32), (0.30, 0.20, 0.14), (0.80, 0.78, 0.72), (0.12, 0.42, 0.44),
                             (0.66, 0.16, 0.50)),
              shelf_height=(0.3, 2.0), tiles=0.5, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # o: held out from issue #29's twenty-fourth round, rendered after its final reader (a
    # shadow's caster at least a quarter cell) and not looked at until scored once. Dome, box
    # and box-with-a-dome robots, ring, cross and ellipse goals, light cool grey, mid sand and
    # dark slate floors tiled every quarter cell, off-white, dark green, rust, dusty blue and
    # dark plum shelves, from 0.3 to 2.0 high inset 0.05 cell, a sun 20-70 degrees up of
    # strength 2.3-3.7, warmer and cooler light, and a camera from 45 to 165 cells per 24 high.
    "o": dict(robot_shapes=("dome", "box", "boxdome"), goal_shapes=("ring", "cross", "ellipse"),
              floors=((0.68, 0.70, 0.72), (0.62, 0.54, 0.40), (0.24, 0.26, 0.30)),
              shelf_colours=((0.90, 0.88, 0.84), (0.10, 0.26, 0.14), (0.62, 0.28, 0.12), (0.44, 0.52, 0.66),
                             (0.30, 0.14, 0.26)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # p: held out from issue #29's twenty-fourth round, rendered after its final reader (one sun
    # for three quarters of the shadows) and not looked at until scored once. Puck, cylinder and
    # rotated-box robots, disc, cross and diamond goals, light beige, mid grey-green and dark
    # warm-brown floors tiled every third of a cell, pale grey, dark brown-black, ochre, navy
    # and salmon shelves, from 0.3 to 2.1 high inset 0.07 cell, a sun 20-70 degrees up of
    # strength 2.3-3.7, warmer and cooler light, and a camera from 45 to 165 cells per 24 high.
    "p": dict(robot_shapes=("puck", "cylinder", "rotbox"), goal_shapes=("disc", "cross", "diamond"),
              floors=((0.76, 0.70, 0.60), (0.46, 0.52, 0.46), (0.30, 0.24, 0.20)),
              shelf_colours=((0.78, 0.78, 0.76), (0.16, 0.13, 0.11), (0.80, 0.60, 0.20), (0.14, 0.18, 0.42),
                             (0.88, 0.52, 0.44)),
              shelf_height=(0.3, 2.1), tiles=1 / 3, shelf_inset=0.07, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # q: held out from issue #29's twenty-sixth round, rendered after its final reader (a run's
    # lean measured beside it, a blocked cell's cover running on, a top read partly as floor)
    # and not looked at until scored once. Box, dome and cylinder robots, square, ring and
    # cross goals, mid grey-green, light warm stone and dark charcoal floors tiled every half
    # cell, mustard, slate blue, brick, pale mint and dark olive shelves, from 0.3 to 2.2 high
    # inset 0.06 cell, a sun 20-70 degrees up of strength 2.3-3.7, warmer and cooler light, and
    # a camera from 45 to 165 cells per 24 high.
    "q": dict(robot_shapes=("box", "dome", "cylinder"), goal_shapes=("square", "ring", "cross"),
              floors=((0.56, 0.60, 0.54), (0.80, 0.76, 0.68), (0.20, 0.21, 0.23)),
              shelf_colours=((0.75, 0.62, 0.18), (0.30, 0.38, 0.55), (0.60, 0.25, 0.18), (0.70, 0.80, 0.72),
                             (0.25, 0.28, 0.12)),
              shelf_height=(0.3, 2.2), tiles=0.5, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # r: held out from issue #29's twenty-sixth round, rendered after its last rule (a long lean
    # needs its face, after q was scored) and not looked at until scored once. Rotated-box,
    # box-with-a-dome and puck robots, ellipse, diamond and disc goals, light blue-grey, mid
    # tan-brown and dark green-black floors tiled every quarter cell, teal, cream, maroon,
    # steel blue and khaki shelves, from 0.3 to 2.1 high inset 0.05 cell, a sun 20-70 degrees
    # up of strength 2.3-3.7, warmer and cooler light, and a camera from 45 to 165 cells per
    # 24 high.
    "r": dict(robot_shapes=("rotbox", "boxdome", "puck"), goal_shapes=("ellipse", "diamond", "disc"),
              floors=((0.64, 0.66, 0.70), (0.52, 0.44, 0.36), (0.16, 0.18, 0.16)),
              shelf_colours=((0.15, 0.50, 0.48), (0.88, 0.84, 0.70), (0.45, 0.12, 0.15), (0.40, 0.50, 0.65),
                             (0.60, 0.56, 0.35)),
              shelf_height=(0.3, 2.1), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # s: held out from issue #29's twenty-seventh round, rendered after its reader (a
    # half-covered cell a mark stands on is free) and not looked at until scored once.
    # Cylinder, rotated-box and dome robots, cross, disc and square goals, warm grey, pale sand
    # and dark slate floors tiled every third of a cell, orange, pale grey-blue, forest green,
    # plum and dark grey shelves, from 0.3 to 2.0 high inset 0.06 cell, a sun 20-70 degrees up
    # of strength 2.3-3.7, warmer and cooler light, and a camera from 45 to 165 cells per 24
    # high.
    "s": dict(robot_shapes=("cylinder", "rotbox", "dome"), goal_shapes=("cross", "disc", "square"),
              floors=((0.58, 0.55, 0.52), (0.82, 0.78, 0.66), (0.22, 0.24, 0.28)),
              shelf_colours=((0.85, 0.45, 0.12), (0.66, 0.72, 0.80), (0.14, 0.32, 0.18), (0.42, 0.20, 0.40),
                             (0.22, 0.22, 0.22)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # t: held out from issue #29's twenty-seventh round, rendered after its final reader (the
    # robots' shadows tell the sun; a top where another's shadow falls may be that shadow)
    # and not looked at until scored once. Puck, box-with-a-dome and box robots, ring, diamond
    # and ellipse goals, mid blue-grey, light warm beige and dark brown-grey floors tiled every
    # half cell, red-brown, light grey, teal blue, sand and dark navy shelves, from 0.3 to 2.1
    # high inset 0.05 cell, a sun 20-70 degrees up of strength 2.3-3.7, warmer and cooler
    # light, and a camera from 45 to 165 cells per 24 high.
    "t": dict(robot_shapes=("puck", "boxdome", "box"), goal_shapes=("ring", "diamond", "ellipse"),
              floors=((0.48, 0.52, 0.58), (0.78, 0.72, 0.62), (0.26, 0.23, 0.21)),
              shelf_colours=((0.50, 0.20, 0.12), (0.80, 0.80, 0.78), (0.12, 0.40, 0.50), (0.72, 0.64, 0.45),
                             (0.10, 0.12, 0.25)),
              shelf_height=(0.3, 2.1), tiles=0.5, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # u and v: held out from issue #29's twenty-seventh round, rendered after its final reader,
    # with t, and not looked at until scored once. u: cylinder, puck and dome robots, disc,
    # square and cross goals, light cool grey, mid olive-grey and dark blue-black floors tiled
    # every quarter cell, brick red, pale lilac, mid green, light tan and charcoal shelves from
    # 0.3 to 2.2 high inset 0.06 cell. v: rotated-box, box and box-with-a-dome robots, ellipse,
    # ring and diamond goals, pale cream, mid warm taupe and dark teal-grey floors tiled every
    # third of a cell, deep blue, off-white, rust, grey-green and plum shelves from 0.3 to 1.9
    # high inset 0.07 cell. Both: a sun 20-70 degrees up of strength 2.3-3.7, warmer and
    # cooler light, and a camera from 45 to 165 cells per 24 high.
    "u": dict(robot_shapes=("cylinder", "puck", "dome"), goal_shapes=("disc", "square", "cross"),
              floors=((0.70, 0.72, 0.74), (0.50, 0.50, 0.40), (0.14, 0.15, 0.20)),
              shelf_colours=((0.55, 0.18, 0.14), (0.78, 0.72, 0.86), (0.25, 0.50, 0.25), (0.80, 0.70, 0.55),
                             (0.18, 0.18, 0.20)),
              shelf_height=(0.3, 2.2), tiles=0.25, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    "v": dict(robot_shapes=("rotbox", "box", "boxdome"), goal_shapes=("ellipse", "ring", "diamond"),
              floors=((0.86, 0.82, 0.70), (0.52, 0.46, 0.40), (0.20, 0.26, 0.26)),
              shelf_colours=((0.10, 0.18, 0.50), (0.90, 0.88, 0.84), (0.60, 0.30, 0.12), (0.45, 0.52, 0.42),
                             (0.40, 0.18, 0.36)),
              shelf_height=(0.3, 1.9), tiles=1 / 3, shelf_inset=0.07, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # w: held out from issue #29's twenty-seventh round, rendered after its last reader change
    # (a top where a shadow falls refused only when darker than the lit floor) and not looked
    # at until scored once. Dome, rotated-box and cylinder robots, square, ellipse and cross
    # goals, mid grey, light sandstone and dark olive-black floors tiled every half cell,
    # saffron, light blue, burgundy, stone grey and dark green shelves from 0.3 to 2.0 high
    # inset 0.05 cell, a sun 20-70 degrees up of strength 2.3-3.7, warmer and cooler light,
    # and a camera from 45 to 165 cells per 24 high.
    "w": dict(robot_shapes=("dome", "rotbox", "cylinder"), goal_shapes=("square", "ellipse", "cross"),
              floors=((0.55, 0.55, 0.55), (0.80, 0.70, 0.56), (0.17, 0.19, 0.13)),
              shelf_colours=((0.90, 0.62, 0.10), (0.55, 0.70, 0.88), (0.42, 0.08, 0.16), (0.62, 0.60, 0.56),
                             (0.10, 0.28, 0.14)),
              shelf_height=(0.3, 2.0), tiles=0.5, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # x and y: held out from issue #29's twenty-seventh round, rendered after w with the same
    # reader and not looked at until scored once. x: puck, box and dome robots, diamond, disc
    # and ring goals, light grey-green, mid brown and dark slate-blue floors tiled every third
    # of a cell, mustard, pale pink, navy, light olive and graphite shelves from 0.3 to 2.2 high
    # inset 0.06 cell. y: box-with-a-dome, cylinder and rotated-box robots, cross, square and
    # ellipse goals, off-white, mid cool grey and dark umber floors tiled every quarter cell,
    # teal, tan, dark red, pale blue-grey and dark olive shelves from 0.3 to 2.0 high inset
    # 0.05 cell. Both: a sun 20-70 degrees up of strength 2.3-3.7, warmer and cooler light,
    # and a camera from 45 to 165 cells per 24 high.
    "x": dict(robot_shapes=("puck", "box", "dome"), goal_shapes=("diamond", "disc", "ring"),
              floors=((0.66, 0.70, 0.62), (0.45, 0.36, 0.28), (0.18, 0.20, 0.27)),
              shelf_colours=((0.78, 0.64, 0.16), (0.88, 0.70, 0.72), (0.10, 0.14, 0.35), (0.60, 0.62, 0.40),
                             (0.24, 0.24, 0.26)),
              shelf_height=(0.3, 2.2), tiles=1 / 3, shelf_inset=0.06, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    "y": dict(robot_shapes=("boxdome", "cylinder", "rotbox"), goal_shapes=("cross", "square", "ellipse"),
              floors=((0.88, 0.86, 0.80), (0.50, 0.52, 0.55), (0.24, 0.18, 0.13)),
              shelf_colours=((0.10, 0.45, 0.45), (0.70, 0.58, 0.42), (0.40, 0.06, 0.08), (0.66, 0.72, 0.76),
                             (0.22, 0.26, 0.10)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),    # z: held out from issue #29's twenty-eighth round, rendered with the reader left as the
    # twenty-seventh round ended it and not looked at until scored once. Rotated-box, dome and
    # cylinder robots, ellipse, disc and cross goals, pale sage, terracotta and dark
    # charcoal-green floors tiled every half cell, blue, cream, plum, sage-grey and graphite
    # shelves from 0.3 to 2.1 high inset 0.07 cell, a sun 20-70 degrees up of strength
    # 2.3-3.7, warmer and cooler light, and a camera from 45 to 165 cells per 24 high.
    "z": dict(robot_shapes=("rotbox", "dome", "cylinder"), goal_shapes=("ellipse", "disc", "cross"),
              floors=((0.70, 0.74, 0.66), (0.55, 0.38, 0.30), (0.16, 0.19, 0.17)),
              shelf_colours=((0.20, 0.40, 0.70), (0.85, 0.78, 0.55), (0.50, 0.15, 0.35), (0.45, 0.55, 0.45),
                             (0.30, 0.28, 0.26)),
              shelf_height=(0.3, 2.1), tiles=0.5, shelf_inset=0.07, warm=0.3, camera_height=(45, 165),
              sun_elevation=(20, 70), sun_power=(2.3, 3.7)),
    # 0 (a digit: the letters are used up): held out after issue #29's twenty-ninth round's
    # painted lines (lined.rs). Box and puck robots, square, ring and diamond goals, dark warm
    # brown, pale grey-blue and olive-grey floors tiled every third of a cell, teal, mustard,
    # off-white, maroon and slate shelves from 0.3 to 2.0 high inset 0.05 cell, a sun 25-75
    # degrees up of strength 2.2-3.6, and a camera from 45 to 165 cells per 24 high.
    "0": dict(robot_shapes=("box", "puck"), goal_shapes=("square", "ring", "diamond"),
              floors=((0.30, 0.24, 0.20), (0.68, 0.72, 0.78), (0.48, 0.50, 0.40)),
              shelf_colours=((0.15, 0.50, 0.55), (0.75, 0.60, 0.15), (0.85, 0.85, 0.82), (0.45, 0.12, 0.15),
                             (0.35, 0.40, 0.48)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.05, warm=0.3, camera_height=(45, 165),
              sun_elevation=(25, 75), sun_power=(2.2, 3.6)),
    # 1: held out after issue #29's thirtieth round (robots under a highlight, robots against
    # shelves of their hue, tops of a colour between over one cell). Box-and-dome, puck and
    # turned-box robots, ring, ellipse and diamond goals, mid-grey, pale straw and dark slate-blue
    # floors tiled every half cell, salmon, bottle-green, light grey, navy and tan shelves from
    # 0.3 to 1.9 high inset 0.06 cell, a sun 30-70 degrees up of strength 2.4-3.8, and a camera
    # from 50 to 160 cells per 24 high.
    "1": dict(robot_shapes=("boxdome", "puck", "rotbox"), goal_shapes=("ring", "ellipse", "diamond"),
              floors=((0.50, 0.50, 0.50), (0.78, 0.72, 0.52), (0.20, 0.24, 0.32)),
              shelf_colours=((0.85, 0.50, 0.42), (0.10, 0.35, 0.20), (0.80, 0.80, 0.80), (0.10, 0.15, 0.40),
                             (0.65, 0.50, 0.32)),
              shelf_height=(0.3, 1.9), tiles=0.5, shelf_inset=0.06, warm=0.3, camera_height=(50, 160),
              sun_elevation=(30, 70), sun_power=(2.4, 3.8)),
    # 2: held out after issue #29's thirty-first round (faint tops judged away from the
    # nadir). Cylinder, dome and box robots, cross, square and disc goals, warm beige, dark
    # green-grey and light cool grey floors tiled every quarter cell, pale blue-grey, rust, dark
    # olive, off-white and purple shelves from 0.3 to 2.0 high inset 0.04 cell, a sun 30-75
    # degrees up of strength 2.3-3.7, and a camera from 50 to 150 cells per 24 high.
    "2": dict(robot_shapes=("cylinder", "dome", "box"), goal_shapes=("cross", "square", "disc"),
              floors=((0.72, 0.66, 0.56), (0.28, 0.32, 0.28), (0.66, 0.68, 0.72)),
              shelf_colours=((0.62, 0.68, 0.74), (0.60, 0.30, 0.18), (0.30, 0.32, 0.12), (0.88, 0.86, 0.80),
                             (0.35, 0.20, 0.50)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.04, warm=0.3, camera_height=(50, 150),
              sun_elevation=(30, 75), sun_power=(2.3, 3.7)),
    # 4: held out after issue #29's thirty-first round's last rule (a pale top on an even
    # floor, looks::ring_limit). Puck, box-and-dome and cylinder robots, diamond, ellipse and
    # ring goals, light sand, mid blue-grey and dark brown-grey floors tiled every third of a
    # cell, off-white, teal, salmon-pink, dark navy and olive-green shelves from 0.3 to 2.0
    # high inset 0.05 cell, a sun 25-80 degrees up of strength 2.2-3.8, and a camera from 45 to
    # 160 cells per 24 high.
    "4": dict(robot_shapes=("puck", "boxdome", "cylinder"), goal_shapes=("diamond", "ellipse", "ring"),
              floors=((0.78, 0.72, 0.60), (0.44, 0.48, 0.55), (0.30, 0.27, 0.25)),
              shelf_colours=((0.90, 0.88, 0.84), (0.15, 0.45, 0.45), (0.85, 0.55, 0.50), (0.10, 0.12, 0.30),
                             (0.40, 0.45, 0.20)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.05, warm=0.3, camera_height=(45, 160),
              sun_elevation=(25, 80), sun_power=(2.2, 3.8)),
    # 8: held out after issue #29's thirty-second round (painted lines measured by colour,
    # faint lines against the cells' middles). Dome, turned-box and puck robots, square, cross
    # and ellipse goals, mid warm grey, dark blue-grey and pale warm white floors tiled every
    # quarter cell, pale grey-green, plum, mid blue, straw and charcoal shelves from 0.3 to 2.0
    # high inset 0.05 cell, a sun 25-80 degrees up of strength 2.3-3.8, and a camera from 45 to
    # 160 cells per 24 high.
    "8": dict(robot_shapes=("dome", "rotbox", "puck"), goal_shapes=("square", "cross", "ellipse"),
              floors=((0.60, 0.58, 0.55), (0.36, 0.40, 0.46), (0.80, 0.78, 0.74)),
              shelf_colours=((0.70, 0.72, 0.70), (0.55, 0.15, 0.35), (0.20, 0.30, 0.60), (0.85, 0.75, 0.40),
                             (0.25, 0.25, 0.25)),
              shelf_height=(0.3, 2.0), tiles=0.25, shelf_inset=0.05, warm=0.3, camera_height=(45, 160),
              sun_elevation=(25, 80), sun_power=(2.3, 3.8)),
    # 9: held out after issue #29's thirty-second round's last rule (each border judged along
    # the lines' colour). Cylinder, box-and-dome and turned-box robots, disc, diamond and cross
    # goals, dark charcoal, light tan and mid green-grey floors tiled every third of a cell,
    # light grey, orange, deep blue, dusty pink and dark olive shelves from 0.3 to 2.0 high
    # inset 0.06 cell, a sun 25-80 degrees up of strength 2.2-3.8, and a camera from 45 to 160
    # cells per 24 high.
    "9": dict(robot_shapes=("cylinder", "boxdome", "rotbox"), goal_shapes=("disc", "diamond", "cross"),
              floors=((0.22, 0.22, 0.24), (0.74, 0.68, 0.56), (0.46, 0.52, 0.46)),
              shelf_colours=((0.78, 0.78, 0.76), (0.85, 0.45, 0.12), (0.12, 0.18, 0.45), (0.70, 0.50, 0.52),
                             (0.30, 0.32, 0.16)),
              shelf_height=(0.3, 2.0), tiles=1 / 3, shelf_inset=0.06, warm=0.3, camera_height=(45, 160),
              sun_elevation=(25, 80), sun_power=(2.2, 3.8)),
}


def parse_range(text, cast=int):
    lo, _, hi = text.partition("-")
    return cast(lo), cast(hi or lo)


def floor_texture(rng, w, h, px, base, lines, tiles=None):
    """The floor as an RGB array, px texels per cell: base colour, stains, grain, tile seams
    (every `tiles` cells, when given), painted lines."""
    tw, th = w * px, h * px
    coarse = rng.normal(0.0, 1.0, (h // 3 + 2, w // 3 + 2))
    stain = np.array(Image.fromarray(coarse.astype(np.float32)).resize((tw, th), Image.BICUBIC))
    grain = rng.normal(0.0, 1.0, (th, tw))
    shade = 1.0 + 0.05 * stain + 0.03 * grain
    if tiles:
        step = max(2, int(round(tiles * px)))
        seam = np.zeros((th, tw), bool)
        seam[::step, :] = True
        seam[:, ::step] = True
        shade = np.where(seam, shade * 0.85, shade)
    tex = np.clip(np.array(base)[None, None, :] * shade[:, :, None], 0, 1)
    if lines:
        width = max(1, int(round(lines["width"] * px)))
        colour = np.array(lines["colour"])
        for k in range(w + 1):
            x0 = min(max(k * px - width // 2, 0), tw - width)
            tex[:, x0:x0 + width] = colour
        for k in range(h + 1):
            y0 = min(max(k * px - width // 2, 0), th - width)
            tex[y0:y0 + width, :] = colour
    return tex


def pick_layout(rng, w, h, n_robots, fam, robot_size, goal_size):
    """Shelves (runs of cells), robot and goal centres: robots never touch anything."""
    blocked = np.zeros((h, w), bool)
    shelves = []
    for _ in range(int(rng.integers(0, max(1, w * h // 25)))):
        length = int(rng.integers(2, 7))
        horizontal = rng.random() < 0.5
        sw, sh = (length, 1) if horizontal else (1, length)
        x, y = int(rng.integers(0, max(1, w - sw))), int(rng.integers(0, max(1, h - sh)))
        if blocked[max(0, y - 1):y + sh + 1, max(0, x - 1):x + sw + 1].any():
            continue
        blocked[y:y + sh, x:x + sw] = True
        shelves.append(dict(x=x, y=y, w=sw, h=sh, height=float(rng.uniform(*fam.get("shelf_height", (0.4, 1.6)))),
                            colour=fam["shelf_colours"][int(rng.integers(len(fam["shelf_colours"])))]))
    free = [(x, y) for y in range(h) for x in range(w) if not blocked[y, x]]
    order = rng.permutation(len(free))
    robots, goals = [], []
    taken = []  # (cx, cy, half size) of everything placed
    reach = lambda s: s / 2 + 0.1

    def fits(cx, cy, half):
        for ox, oy, oh in taken:
            if abs(cx - ox) < half + oh and abs(cy - oy) < half + oh:
                return False
        x0, x1 = int(math.floor(cx - half)), int(math.floor(cx + half))
        y0, y1 = int(math.floor(cy - half)), int(math.floor(cy + half))
        if x0 < 0 or y0 < 0 or x1 >= w or y1 >= h:
            return False
        return not blocked[y0:y1 + 1, x0:x1 + 1].any()

    for i in order:
        if len(robots) == n_robots and len(goals) == n_robots:
            break
        x, y = free[i]
        want_robot = len(robots) < n_robots and (len(goals) >= n_robots or rng.random() < 0.5)
        size = robot_size if want_robot else goal_size
        cx = x + 0.5 + rng.uniform(-0.22, 0.22)
        cy = y + 0.5 + rng.uniform(-0.22, 0.22)
        if not fits(cx, cy, reach(size)):
            continue
        taken.append((cx, cy, reach(size)))
        (robots if want_robot else goals).append((cx, cy))
    return blocked, shelves, robots, goals


def camera(rng, w, h, cell_px, tilt_max, cam_height=(60, 140)):
    """A pinhole camera over the floor: position, target, up, horizontal fov, image size."""
    tilt = math.radians(rng.uniform(0, tilt_max)) if tilt_max > 0 and rng.random() < 0.6 else 0.0
    azim = rng.uniform(0, 2 * math.pi)
    height = rng.uniform(*cam_height) * max(w, h) / 24
    centre = np.array([w / 2, h / 2, 0.0])
    offset = np.array([math.sin(tilt) * math.cos(azim), math.sin(tilt) * math.sin(azim), math.cos(tilt)])
    origin = centre + offset * height
    up = np.array([0.0, 1.0, 0.0])
    if tilt == 0:
        # Straight down: the floor fills the image exactly.
        fov = 2 * math.degrees(math.atan((w / 2) / height))
        return dict(origin=origin, target=centre, up=up, fov=fov,
                    size=(int(round(w * cell_px)), int(round(h * cell_px))), tilt=0.0)
    cam = dict(origin=origin, target=centre, up=up, fov=1.0, size=(1, 1), tilt=math.degrees(tilt))
    corners = [(0, 0), (w, 0), (w, h), (0, h)]
    pts = np.array([project_unit(cam, (x, h - y, 0.0)) for x, y in corners])
    half_x = np.abs(pts[:, 0]).max() * 1.06
    half_y = np.abs(pts[:, 1]).max() * 1.06
    side = math.hypot(w, h)
    # Pixels per unit of the normalised plane such that the floor's mean cell is cell_px wide.
    scale = cell_px * side / math.hypot(pts[1, 0] - pts[3, 0] + 1e-9, pts[2, 1] - pts[0, 1] + 1e-9)
    size = (int(2 * half_x * scale), int(2 * half_y * scale))
    cam["fov"] = 2 * math.degrees(math.atan(half_x))
    cam["size"] = size
    return cam


def frame(cam):
    d = cam["target"] - cam["origin"]
    d = d / np.linalg.norm(d)
    right = np.cross(d, cam["up"])
    if np.linalg.norm(right) < 1e-9:
        right = np.array([1.0, 0.0, 0.0])
    right = right / np.linalg.norm(right)
    down = np.cross(d, right)
    return d, right, down


def project_unit(cam, p):
    d, right, down = frame(cam)
    q = np.array(p) - cam["origin"]
    z = q @ d
    return (q @ right) / z, (q @ down) / z


def project(cam, p):
    """Image pixel (x right, y down; pixel centres at +0.5) of a world point."""
    u, v = project_unit(cam, p)
    wpx, hpx = cam["size"]
    f = (wpx / 2) / math.tan(math.radians(cam["fov"]) / 2)
    return (wpx / 2 + u * f, hpx / 2 + v * f)


def mitsuba_camera(cam, spp):
    d, right, down = frame(cam)
    # Mitsuba's look_at puts image x along cross(up, dir); give it the up that makes that
    # our `right`: up' = -down.
    return {
        "type": "perspective",
        "fov": cam["fov"], "fov_axis": "x",
        "to_world": mi.ScalarTransform4f().look_at(origin=list(cam["origin"]), target=list(cam["target"]), up=list(-down)),
        "sampler": {"type": "independent", "sample_count": spp},
        "film": {"type": "hdrfilm", "width": cam["size"][0], "height": cam["size"][1],
                 "rfilter": {"type": "gaussian"}, "pixel_format": "rgb"},
    }


def diffuse(rgb):
    return {"type": "diffuse", "reflectance": {"type": "rgb", "value": list(rgb)}}


def plastic(rgb, rough):
    return {"type": "roughplastic", "distribution": "ggx", "alpha": rough,
            "diffuse_reflectance": {"type": "rgb", "value": list(rgb)}}


def box(cx, cy, z0, sx, sy, sz, bsdf, yaw=0.0):
    T = mi.ScalarTransform4f()
    to_world = T.translate([cx, cy, z0 + sz / 2])
    if yaw:
        to_world = to_world.rotate([0, 0, 1], yaw)
    to_world = to_world.scale([sx / 2, sy / 2, sz / 2])
    return {"type": "cube", "to_world": to_world, "bsdf": bsdf}


def scene_dict(rng, fam, args, w, h, cell_px, tex_path, shelves, robots, goals, cam, robot, goal, light):
    T = mi.ScalarTransform4f()
    objs = {
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": mitsuba_camera(cam, args.spp),
        "floor": {"type": "rectangle",
                  "to_world": T.translate([w / 2, h / 2, 0]).scale([w / 2, h / 2, 1]),
                  "bsdf": {"type": "diffuse", "reflectance": {"type": "bitmap", "filename": tex_path}}},
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": light["sky"]}},
    }
    sun = np.array(light["sun_dir"])
    if light["soft"]:
        # A sphere far away in the sun's direction: its apparent size makes the penumbra.
        dist = 400.0 * max(w, h) / 24
        radius = dist * math.tan(math.radians(light["soft"]))
        centre = np.array([w / 2, h / 2, 0]) + sun * dist
        power = np.array(light["sun"]) * (dist / radius) ** 2 / math.pi
        objs["sun"] = {"type": "sphere", "center": list(centre), "radius": radius,
                       "emitter": {"type": "area", "radiance": {"type": "rgb", "value": list(power)}}}
    else:
        objs["sun"] = {"type": "directional", "direction": list(-sun),
                       "irradiance": {"type": "rgb", "value": light["sun"]}}
    inset = fam.get("shelf_inset", 0.02)
    for i, s in enumerate(shelves):
        objs[f"shelf{i}"] = box(s["x"] + s["w"] / 2, h - (s["y"] + s["h"] / 2), 0, s["w"] - 2 * inset,
                                s["h"] - 2 * inset, s["height"], plastic(s["colour"], 0.3))
    for i, (cx, cy) in enumerate(robots):
        cy = h - cy
        col = robot["colour"] * rng.uniform(0.85, 1.1)
        mat = plastic(np.clip(col, 0, 1), robot["rough"])
        r, hgt = robot["size"] / 2, robot["height"]
        if robot["shape"] == "box":
            objs[f"robot{i}"] = box(cx, cy, 0, 2 * r, 2 * r, hgt, mat)
        elif robot["shape"] == "rotbox":
            # A box of the same footprint area as the cylinder, turned about its axis.
            side = r * math.sqrt(math.pi)
            objs[f"robot{i}"] = box(cx, cy, 0, side, side, hgt, mat, yaw=float(rng.uniform(0, 90)))
        elif robot["shape"] == "boxdome":
            # A box with a dome (half its width) on top.
            objs[f"robot{i}"] = box(cx, cy, 0, 2 * r, 2 * r, hgt, mat)
            objs[f"robot{i}top"] = {"type": "sphere", "center": [cx, cy, hgt], "radius": 0.5 * r, "bsdf": mat}
        elif robot["shape"] == "puck":
            objs[f"robot{i}"] = {"type": "cylinder", "p0": [cx, cy, 0], "p1": [cx, cy, hgt], "radius": r, "bsdf": mat}
            objs[f"robot{i}top"] = {"type": "disk", "to_world": T.translate([cx, cy, hgt]).scale([r, r, 1]), "bsdf": mat}
            cap = plastic(np.clip(col * 0.45, 0, 1), robot["rough"])
            objs[f"robot{i}cap"] = {"type": "cylinder", "p0": [cx, cy, hgt], "p1": [cx, cy, hgt + 0.15 * hgt],
                                    "radius": 0.45 * r, "bsdf": cap}
            objs[f"robot{i}capt"] = {"type": "disk", "to_world": T.translate([cx, cy, hgt + 0.15 * hgt]).scale([0.45 * r, 0.45 * r, 1]),
                                     "bsdf": cap}
        else:
            objs[f"robot{i}"] = {"type": "cylinder", "p0": [cx, cy, 0], "p1": [cx, cy, hgt], "radius": r, "bsdf": mat}
            if robot["shape"] == "dome":
                objs[f"robot{i}top"] = {"type": "sphere", "center": [cx, cy, hgt], "radius": r, "bsdf": mat}
            else:
                objs[f"robot{i}top"] = {"type": "disk", "to_world": T.translate([cx, cy, hgt]).scale([r, r, 1]), "bsdf": mat}
    for i, (cx, cy) in enumerate(goals):
        cy = h - cy
        mat = diffuse(goal["colour"])
        r = goal["size"] / 2
        z = 0.003
        if goal["shape"] == "square":
            objs[f"goal{i}"] = box(cx, cy, 0, 2 * r, 2 * r, z, mat)
        elif goal["shape"] == "diamond":
            objs[f"goal{i}"] = box(cx, cy, 0, 2 * r / math.sqrt(2), 2 * r / math.sqrt(2), z, mat, yaw=45.0)
        elif goal["shape"] == "ellipse":
            # A disc squashed to 0.6 across, turned.
            to_world = T.translate([cx, cy, z]).rotate([0, 0, 1], float(rng.uniform(0, 180))).scale([r, max(0.6 * r, 1.75 / cell_px), 1])
            objs[f"goal{i}"] = {"type": "disk", "to_world": to_world, "bsdf": mat}
        elif goal["shape"] == "cross":
            objs[f"goal{i}"] = box(cx, cy, 0, 2 * r, 0.7 * r, z, mat)
            objs[f"goal{i}b"] = box(cx, cy, 0, 0.7 * r, 2 * r, z, mat)
        else:
            objs[f"goal{i}"] = {"type": "disk", "to_world": T.translate([cx, cy, z]).scale([r, r, 1]), "bsdf": mat}
            if goal["shape"] == "ring":
                objs[f"goal{i}in"] = {"type": "disk", "to_world": T.translate([cx, cy, 2 * z]).scale([r * 0.45, r * 0.45, 1]),
                                      "bsdf": diffuse(np.array(goal["colour"]) * 0.55)}
    return objs


def blur(img, sigma):
    if sigma <= 0:
        return img
    rad = max(1, int(3 * sigma))
    k = np.exp(-0.5 * (np.arange(-rad, rad + 1) / sigma) ** 2)
    k /= k.sum()
    pad = np.pad(img, ((rad, rad), (rad, rad), (0, 0)), mode="edge")
    tmp = sum(k[i] * pad[:, i:i + img.shape[1]] for i in range(len(k)))
    return sum(k[i] * tmp[i:i + img.shape[0]] for i in range(len(k)))


def draw_scene(args, seed):
    """The scene's random draws up to its layout, in the order render_one makes them: the
    generator (to draw on), the family, the grid, pixels per cell, the robots' and goals' looks,
    and the layout. census.py draws a layout again with it."""
    fam = FAMILIES[args.family]
    rng = np.random.default_rng([ord(args.family), seed])
    if args.cells:
        w, h = parse_range(args.cells.replace("x", "-"))
    else:
        w, h = int(rng.integers(10, 33)), int(rng.integers(8, 25))
    cell_px = float(rng.uniform(*parse_range(args.cell_px, float)))
    n_lo, n_hi = parse_range(args.robots)
    n = int(rng.integers(n_lo, n_hi + 1))
    big = rng.random() < 0.2
    robot = dict(shape=fam["robot_shapes"][int(rng.integers(len(fam["robot_shapes"])))],
                 size=float(rng.uniform(1.3, 1.8) if big else rng.uniform(0.35, 0.8)),
                 height=float(rng.uniform(0.15, 0.6)), rough=float(rng.uniform(0.1, 0.5)),
                 colour=np.array([rng.uniform(0.55, 0.85), rng.uniform(0.02, 0.1), rng.uniform(0.02, 0.1)]))
    goal = dict(shape=fam["goal_shapes"][int(rng.integers(len(fam["goal_shapes"])))],
                size=float(rng.uniform(0.35, 0.8)),
                colour=[rng.uniform(0.03, 0.15), rng.uniform(0.4, 0.65), rng.uniform(0.05, 0.2)])
    # A robot at least 3 px wide: the reader's smallest blob.
    robot["size"] = max(robot["size"], 3.5 / cell_px)
    goal["size"] = max(goal["size"], 3.5 / cell_px)
    blocked, shelves, robots, goals = pick_layout(rng, w, h, n, fam, robot["size"], goal["size"])
    n = min(len(robots), len(goals))
    return rng, fam, (w, h), cell_px, robot, goal, (blocked, shelves, robots[:n], goals[:n])


def draw_view(args, seed):
    """The scene's random draws up to its camera, in the order render_one makes them: those of
    draw_scene, then the floor's colour, painted lines and texture, the light and the camera.
    visibility.py draws a view again with it (no rendering)."""
    rng, fam, (w, h), cell_px, robot, goal, (blocked, shelves, robots, goals) = draw_scene(args, seed)
    base = fam["floors"][int(rng.integers(len(fam["floors"])))]
    lines = None
    if rng.random() < args.lines:
        lines = dict(width=float(rng.uniform(0.04, 0.09)),
                     colour=[0.12, 0.12, 0.12] if rng.random() < 0.6 else [0.92, 0.92, 0.9])
    tex_px = int(min(24, max(8, 4096 // max(w, h))))
    tex = floor_texture(rng, w, h, tex_px, base, lines, fam.get("tiles"))
    elev = math.radians(rng.uniform(*fam.get("sun_elevation", (35, 80))))
    az = rng.uniform(0, 2 * math.pi)
    warm = rng.uniform(-fam.get("warm", 0.15), fam.get("warm", 0.15))
    # Families before F: a sun of strength 3, drawing nothing (their scenes stay as rendered).
    power = float(rng.uniform(*fam["sun_power"])) if "sun_power" in fam else 3.0
    light = dict(sun_dir=[math.cos(elev) * math.cos(az), math.cos(elev) * math.sin(az), math.sin(elev)],
                 sun=[power * (1 + warm), power, power * (1 - warm)],
                 sky=[0.35 * (1 - warm / 2), 0.38, 0.42 * (1 + warm / 2)],
                 soft=float(rng.uniform(1.0, 6.0)) if rng.random() < 0.5 else 0.0)
    cam = camera(rng, w, h, cell_px, args.tilt, fam.get("camera_height", (60, 140)))
    return dict(rng=rng, fam=fam, grid=(w, h), cell_px=cell_px, robot=robot, goal=goal, blocked=blocked,
                shelves=shelves, robots=robots, goals=goals, lines=lines, tex=tex, light=light, cam=cam)


def render_one(args, seed, out_dir):
    v = draw_view(args, seed)
    rng, fam, (w, h), cell_px, robot, goal = v["rng"], v["fam"], v["grid"], v["cell_px"], v["robot"], v["goal"]
    blocked, shelves, robots, goals = v["blocked"], v["shelves"], v["robots"], v["goals"]
    lines, light, cam = v["lines"], v["light"], v["cam"]
    tex_path = os.path.join(out_dir, f".floor-{args.family}{seed}.png")
    Image.fromarray((v["tex"] * 255).astype(np.uint8)).save(tex_path)
    mi_scene = mi.load_dict(scene_dict(rng, fam, args, w, h, cell_px, tex_path, shelves, robots, goals,
                                       cam, robot, goal, light))
    img = np.array(mi.render(mi_scene, seed=seed))
    os.remove(tex_path)
    exposure = rng.uniform(0.45, 0.7)
    img = np.clip(img * exposure, 0, None)
    img = np.where(img <= 0.0031308, 12.92 * img, 1.055 * np.power(img, 1 / 2.4) - 0.055)
    img = blur(img, float(rng.uniform(0, 1.0)))
    noise = float(rng.uniform(0, 0.025))
    img = np.clip(img + rng.normal(0, noise, img.shape), 0, 1)
    pixels = Image.fromarray((img * 255 + 0.5).astype(np.uint8))
    name = f"{args.family}{seed:04d}"
    quality = int(rng.integers(60, 96)) if rng.random() < args.jpeg else None
    if quality:
        path = os.path.join(out_dir, name + ".jpg")
        pixels.save(path, quality=quality)
    else:
        path = os.path.join(out_dir, name + ".png")
        pixels.save(path, optimize=True)
    corners = [project(cam, (x, h - y, 0.0)) for x, y in [(0, 0), (w, 0), (w, h), (0, h)]]
    truth = {
        "image": os.path.basename(path),
        "renderer": f"mitsuba {mi.__version__} scalar_rgb, path tracer, {args.spp} spp",
        "family": args.family, "seed": seed,
        "grid": [w, h],
        "corners": [[round(x, 2), round(y, 2)] for x, y in corners],
        "straight_down": cam["tilt"] == 0,
        "cell_px": cell_px,
        "blocked": [[int(x), int(y)] for y, x in zip(*np.nonzero(blocked))],
        "robots": [[int(cx), int(cy)] for cx, cy in robots],
        "goals": [[int(cx), int(cy)] for cx, cy in goals],
        # The exact layout, for measuring how far a reading's positions are off (the cells
        # above are what a reading must match).
        "robot_centres": [[round(cx, 4), round(cy, 4)] for cx, cy in robots],
        "goal_centres": [[round(cx, 4), round(cy, 4)] for cx, cy in goals],
        "shelves": [{"cells": [s["x"], s["y"], s["w"], s["h"]], "height": round(s["height"], 4),
                     "colour": list(s["colour"])} for s in shelves],
        "params": {"robot": {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in robot.items()},
                   "goal": goal, "lines": lines, "light": light, "tilt_deg": cam["tilt"],
                   "camera_height": float(cam["origin"][2]), "jpeg_quality": quality, "noise": noise,
                   "image_size": list(cam["size"])},
    }
    with open(os.path.join(out_dir, name + ".json"), "w") as f:
        json.dump(truth, f, indent=1)
    return path


def arguments():
    """The command line's parser (census.py takes its defaults)."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--family", default="A", choices=sorted(FAMILIES))
    ap.add_argument("--seeds", default="0-9")
    ap.add_argument("--cells", help="WxH (default: random 10-32 x 8-24)")
    ap.add_argument("--cell-px", default="8-40", help="pixels per cell, a range")
    ap.add_argument("--robots", default="4-30")
    ap.add_argument("--tilt", type=float, default=30.0, help="largest camera tilt in degrees (0: all straight down)")
    ap.add_argument("--lines", type=float, default=0.5, help="share of floors with painted grid lines")
    ap.add_argument("--jpeg", type=float, default=0.5, help="share of images saved as JPEG")
    ap.add_argument("--spp", type=int, default=16)
    return ap


def main():
    args = arguments().parse_args()
    mi.set_variant("scalar_rgb")
    os.makedirs(args.out, exist_ok=True)
    lo, hi = parse_range(args.seeds)
    for seed in range(lo, hi + 1):
        print(render_one(args, seed, args.out), flush=True)


if __name__ == "__main__":
    sys.exit(main())
