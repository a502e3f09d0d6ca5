#!/usr/bin/env python3
"""Writes scenes/library/sdf-circles.json and sdf-wires.json (the analytical-AA test scenes).

Both are flat (unlit, orthographic, disks / capsules facing the camera over quads) so that
`--reference exact` applies. At the default 960x540 one pixel is 1/60 world unit (camera
height 9). Run from the repository root; the output is deterministic.
"""
import json
import math

PX = 9.0 / 540.0  # world units per pixel at 960x540
CAMERA = {"type": "orthographic", "position": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "height": 9}


def frac(i, salt):
    """Deterministic sub-pixel offset in [0, 1) (no two circles share a phase)."""
    return ((i * 0.6180339887498949 + salt * 0.4142135623730951) % 1.0)


def px_to_world(x, y):
    return [round((x - 480.0) * PX, 6), round((270.0 - y) * PX, 6), 0]


def circles():
    radii = [60, 50, 40, 32, 25, 20, 16, 12, 10, 8, 6, 5, 4, 3, 2.5, 2, 1.5, 1.25, 1, 0.75, 0.6, 0.5]
    colours = [("white", [0.9, 0.9, 0.9]), ("grey", [0.3, 0.3, 0.3]), ("red", [0.85, 0.12, 0.1]),
               ("dark", [0.06, 0.06, 0.07])]
    items = [(r, c) for r in radii for c in range(len(colours)) if not (r >= 40 and c == 3)]
    objects = [
        {"shape": "quad", "size": [8.0, 9.0], "transform": {"translate": [-4.0, 0, -1]}, "material": "bg-dark"},
        {"shape": "quad", "size": [8.0, 9.0], "transform": {"translate": [4.0, 0, -1]}, "material": "bg-light"},
    ]
    x, y, row_h, margin = 4.0, 4.0, 0.0, 5.0
    for i, (r, c) in enumerate(items):
        d = 2 * r + margin
        if x + d > 956:
            x, y, row_h = 4.0, y + row_h, 0.0
        cx = x + r + margin / 2 + frac(i, 1)
        cy = y + r + margin / 2 + frac(i, 2)
        assert cy + r < 540, "circles do not fit"
        objects.append({"shape": "disk", "radius": round(r * PX, 7), "transform": {"translate": px_to_world(cx, cy)},
                        "material": colours[c][0]})
        x += d + 1
        row_h = max(row_h, d + 1)
    mats = {name: {"shading": "unlit", "color": col} for name, col in colours}
    mats["bg-dark"] = {"shading": "unlit", "color": [0.03, 0.03, 0.035]}
    mats["bg-light"] = {"shading": "unlit", "color": [0.7, 0.7, 0.65]}
    return {
        "name": "sdf-circles",
        "description": "Analytical-AA test card after the AA article's demo: disks of radius 0.5 to 60 px (at 960x540) "
                       "in white, grey, red and near-black over a dark left half and a light right half, so the "
                       "contrast varies from none to full; sub-pixel centre offsets. Flat: --reference exact applies.",
        "effects": ["unlit"], "camera": CAMERA, "display": {"exposure": 1, "tonemap": "none"},
        "background": [0.03, 0.03, 0.035], "materials": mats, "objects": objects}


def wires():
    widths = [0.25, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0]
    angles = [0, 15, 30, 45, 60, 75, 90, 105, 120, 135, 150, 165]
    objects = [{"shape": "quad", "size": [16.0, 9.0], "transform": {"translate": [0, 0, -1]}, "material": "bg"}]
    cell_w, cell_h, half_len = 80.0, 60.0, 24.0
    for j, w in enumerate(widths):
        for i, a in enumerate(angles):
            cx = cell_w * (i + 0.5) + frac(j * 12 + i, 3) - 0.5
            cy = cell_h * (j + 0.5) + frac(j * 12 + i, 4) - 0.5
            t = math.radians(a)
            dx, dy = half_len * math.cos(t), -half_len * math.sin(t)
            objects.append({"shape": "capsule", "from": px_to_world(cx - dx, cy - dy), "to": px_to_world(cx + dx, cy + dy),
                            "radius": round(0.5 * w * PX, 8), "material": "wire" if (i + j) % 2 == 0 else "wire-dim"})
    return {
        "name": "sdf-wires",
        "description": "Analytical-AA wires: capsules 0.25 to 4 px wide (at 960x540), 48 px long, at 12 angles from 0 to "
                       "165 degrees, bright and dim on a dark ground. Flat: --reference exact applies.",
        "effects": ["unlit"], "camera": CAMERA, "display": {"exposure": 1, "tonemap": "none"},
        "background": [0.02, 0.02, 0.03],
        "materials": {"bg": {"shading": "unlit", "color": [0.04, 0.05, 0.08]},
                      "wire": {"shading": "unlit", "color": [0.95, 0.92, 0.8]},
                      "wire-dim": {"shading": "unlit", "color": [0.35, 0.4, 0.5]}},
        "objects": objects}


for scene in (circles(), wires()):
    with open("scenes/library/%s.json" % scene["name"], "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
