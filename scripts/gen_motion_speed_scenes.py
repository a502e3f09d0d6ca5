#!/usr/bin/env python3
"""Writes the speed-sweep scene family scenes/library/motion-speed-<kind>-<speed>.json.

Four motions (translate, rotate, zoom, disocclude) at 0.25, 0.5, 1, 2, 4 and 8 px per frame,
measured at 320x180 (the sweep's size; orthographic camera 9 units high, so 1 px = 0.05 units;
speeds scale with the output size). 24 frames. Same content in all: a rotated checker layer
(texture) under four flat quads whose edges start near horizontal, near vertical and at 30 and
60 degrees. docs/motion.md "Speed sweep" lists the family; rerun this script after a change.
  translate:  the camera pans at v px/frame along (0.94, 0.34) (a non-axis direction);
  rotate:     each quad turns about its centre so that its corners move v px/frame;
  zoom:       the camera zooms so that the frame's corners move v px/frame at frame 0
              (linear zoom keys: 1 -> 1 + 23 v / 183.6);
  disocclude: a dark foreground bar crosses at v px/frame, uncovering the textured layer.
"""
import json, math, os

PX = 9.0 / 180.0  # world units per pixel at 320x180
FRAMES = 24
SPEEDS = [(0.25, "0p25"), (0.5, "0p5"), (1, "1"), (2, "2"), (4, "4"), (8, "8")]
QUADS = [(-3.2, 1.8, 2.0, "white"), (0.0, 1.8, 30.0, "grey"), (3.2, 1.8, 60.0, "white"),
         (-3.2, -1.8, 88.0, "grey"), (0.0, -1.8, 45.0, "white"), (3.2, -1.8, 15.0, "grey")]
QUAD_SIZE = [2.4, 1.2]
HALF_DIAG_PX = math.hypot(*QUAD_SIZE) / 2 / PX
CORNER_PX = math.hypot(160, 90)


def base(name, description):
    return {
        "name": name,
        "description": description,
        "effects": ["unlit", "textures"],
        "camera": {"type": "orthographic", "position": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "height": 9},
        "display": {"exposure": 1, "tonemap": "none"},
        "background": [0.02, 0.02, 0.025],
        "materials": {
            "checker": {"shading": "unlit", "texture": {"pattern": "checker", "scale": 2,
                                                        "color_a": [0.08, 0.08, 0.1], "color_b": [0.55, 0.55, 0.5]}},
            "white": {"shading": "unlit", "color": [0.9, 0.9, 0.9]},
            "grey": {"shading": "unlit", "color": [0.35, 0.3, 0.25]},
        },
        "objects": [{"shape": "quad", "size": [40, 24], "material": "checker",
                     "transform": {"translate": [0, 0, -0.5], "rotate": [0, 0, 7]}}],
        "animation": {"frames": FRAMES},
    }


def quads(rotate_deg_per_frame=0.0):
    out = []
    for (x, y, a, m) in QUADS:
        o = {"shape": "quad", "size": QUAD_SIZE, "material": m, "transform": {"translate": [x, y, 0], "rotate": [0, 0, a]}}
        if rotate_deg_per_frame:
            o["motion"] = {"pivot": [x, y, 0], "keys": [{"frame": 0},
                                                         {"frame": FRAMES - 1, "rotate": [0, 0, round(rotate_deg_per_frame * (FRAMES - 1), 6)]}]}
        out.append(o)
    return out


def scene(kind, v, tag):
    name = f"motion-speed-{kind}-{tag}"
    what = {
        "translate": "the camera pans",
        "rotate": "quads turn about their centres (corner speed)",
        "zoom": "the camera zooms (speed at the frame corners)",
        "disocclude": "a dark foreground bar crosses, uncovering a textured layer",
    }[kind]
    s = base(name, f"Speed sweep: {what} at {v:g} px per frame at 320x180 (24 frames; checker layer under flat quads).")
    if kind == "translate":
        d = v * (FRAMES - 1) * PX
        s["objects"] += quads()
        s["animation"]["camera"] = [{"frame": 0}, {"frame": FRAMES - 1, "offset": [round(0.94 * d, 6), round(0.34 * d, 6), 0]}]
    elif kind == "rotate":
        s["objects"] += quads(math.degrees(v / HALF_DIAG_PX))
    elif kind == "zoom":
        s["objects"] += quads()
        s["animation"]["camera"] = [{"frame": 0}, {"frame": FRAMES - 1, "zoom": round(1 + (FRAMES - 1) * v / CORNER_PX, 6)}]
    else:
        s["objects"] += quads()
        s["materials"]["bar"] = {"shading": "unlit", "color": [0.12, 0.1, 0.3]}
        d = v * (FRAMES - 1) * PX
        x0 = -d / 2 - 0.3
        s["objects"].append({"shape": "quad", "size": [1.5, 12], "material": "bar",
                             "transform": {"translate": [round(x0, 6), 0, 1], "rotate": [0, 0, 4]},
                             "motion": {"keys": [{"frame": 0}, {"frame": FRAMES - 1, "translate": [round(d, 6), 0, 0]}]}})
    return name, s


def main():
    lib = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "library")
    names = []
    for kind in ["translate", "rotate", "zoom", "disocclude"]:
        for v, tag in SPEEDS:
            name, s = scene(kind, v, tag)
            with open(os.path.join(lib, name + ".json"), "w") as f:
                json.dump(s, f, indent=2)
                f.write("\n")
            names.append(name)
    print("\n".join(names))


if __name__ == "__main__":
    main()
