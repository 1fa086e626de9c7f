"""Draws a scene's ground truth on its image, to check the truth by eye: the grid through the
homography of the truth's corners (yellow), blocked cells (blue), robot centres (magenta) and
goal centres (cyan) where the truth has them (render_blender.py writes them).

    python overlay_truth.py SCENE.json OUT.png [--scale 2]
"""
import json
import os
import sys

import numpy as np
from PIL import Image, ImageDraw


def homography(src, dst):
    a, b = [], []
    for (x, y), (u, v) in zip(src, dst):
        a.append([x, y, 1, 0, 0, 0, -u * x, -u * y])
        b.append(u)
        a.append([0, 0, 0, x, y, 1, -v * x, -v * y])
        b.append(v)
    return np.append(np.linalg.solve(np.array(a, float), np.array(b, float)), 1).reshape(3, 3)


def main():
    truth_path, out = sys.argv[1], sys.argv[2]
    scale = float(sys.argv[sys.argv.index("--scale") + 1]) if "--scale" in sys.argv else 1.0
    t = json.load(open(truth_path))
    im = Image.open(os.path.join(os.path.dirname(truth_path), t["image"])).convert("RGB")
    im = im.resize((int(im.width * scale), int(im.height * scale)), Image.NEAREST)
    w, h = t["grid"]
    hom = homography([(0, 0), (w, 0), (w, h), (0, h)], t["corners"])

    def px(x, y):
        q = hom @ [x, y, 1.0]
        return (q[0] / q[2] * scale, q[1] / q[2] * scale)

    d = ImageDraw.Draw(im)
    for x in range(w + 1):
        d.line([px(x, 0), px(x, h)], fill=(255, 255, 0))
    for y in range(h + 1):
        d.line([px(0, y), px(w, y)], fill=(255, 255, 0))
    for x, y in t["blocked"]:
        d.polygon([px(x, y), px(x + 1, y), px(x + 1, y + 1), px(x, y + 1)], outline=(0, 0, 255))
    for key, colour in (("robot_centres", (255, 0, 255)), ("goal_centres", (0, 255, 255))):
        for cx, cy in t.get(key, []):
            u, v = px(cx, cy)
            d.ellipse([u - 2, v - 2, u + 2, v + 2], fill=colour)
    im.save(out)


if __name__ == "__main__":
    sys.exit(main())
