#!/usr/bin/env python3
"""Generates the game-like glTF scenes of the `real` suite (scenes/library/real/*.glb) and
their aalab scene files (scenes/library/real-*.json): alpha-tested foliage on leaf cards, a
chain-link fence against a bright sky, sub-pixel power lines, a textured floor and wall at
grazing angles, a normal-mapped glossy floor under the sun, distant window grids with signage.

Python 3 standard library only (PNG through zlib, GLB by hand), deterministic: the same
bytes on every run (a fixed linear congruential generator, no dict-order or float-format
surprises). Run from the repository root:  python3 scripts/make_real_scenes.py
"""
import json
import math
import os
import struct
import zlib

OUT_DIR = os.path.join("scenes", "library")
GLB_DIR = os.path.join(OUT_DIR, "real")


class Rng:
    """A 32-bit LCG (Numerical Recipes constants): deterministic across Python versions."""

    def __init__(self, seed):
        self.s = seed & 0xFFFFFFFF

    def next(self):
        self.s = (1664525 * self.s + 1013904223) & 0xFFFFFFFF
        return self.s / 4294967296.0


# --------------------------------------------------------------------------- PNG writing
def png_bytes(w, h, pixels, channels):
    """pixels: list of rows, each a list of `channels`-tuples of ints 0..255."""
    raw = bytearray()
    for row in pixels:
        raw.append(0)
        for p in row:
            raw.extend(p[:channels])
    def chunk(tag, data):
        c = struct.pack(">I", len(data)) + tag + data
        return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    colour_type = {1: 0, 3: 2, 4: 6}[channels]
    ihdr = struct.pack(">IIBBBBB", w, h, 8, colour_type, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b"")


def clamp8(x):
    return max(0, min(255, int(round(x * 255.0))))


def srgb8(linear):
    """Linear value -> sRGB-encoded 8-bit code (textures' colour is stored sRGB-encoded)."""
    x = max(0.0, min(1.0, linear))
    e = 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1.0 / 2.4) - 0.055
    return clamp8(e)


def image(w, h, fn):
    return [[fn(x, y) for x in range(w)] for y in range(h)]


# --------------------------------------------------------------------------- textures
def leaf_texture(n=256):
    """Five leaves on a transparent card: alpha 1 inside each ellipse, a 1-texel ramp."""
    rng = Rng(7)
    leaves = []
    for _ in range(5):
        cx, cy = 0.2 + 0.6 * rng.next(), 0.2 + 0.6 * rng.next()
        ang = rng.next() * math.pi
        leaves.append((cx, cy, ang, 0.18 + 0.08 * rng.next(), 0.06 + 0.03 * rng.next(), rng.next()))
    def px(x, y):
        u, v = (x + 0.5) / n, (y + 0.5) / n
        best = None
        for (cx, cy, ang, a, b, tone) in leaves:
            du, dv = u - cx, v - cy
            lu = du * math.cos(ang) + dv * math.sin(ang)
            lv = -du * math.sin(ang) + dv * math.cos(ang)
            d = math.sqrt((lu / a) ** 2 + (lv / b) ** 2)
            if best is None or d < best[0]:
                best = (d, tone, lu / a, lv / b)
        d, tone, lu, lv = best
        alpha = max(0.0, min(1.0, (1.0 - d) * n * 0.06 + 0.5))
        vein = 0.75 if abs(lv) < 0.06 else 1.0
        g = (0.18 + 0.25 * tone) * vein
        return (srgb8(g * 0.45), srgb8(g), srgb8(g * 0.25), clamp8(alpha))
    return png_bytes(n, n, image(n, n, px), 4)


def chainlink_texture(n=64):
    """One diamond cell of a chain-link fence: two crossing wires of 5 texels, alpha 1 on wire."""
    def px(x, y):
        u, v = (x + 0.5) / n, (y + 0.5) / n
        d1 = abs(((u + v) % 1.0) - 0.5)
        d2 = abs(((u - v) % 1.0) - 0.5)
        wire = min(d1, d2) < 2.5 / n
        shade = 0.55 + 0.3 * (1.0 - min(d1, d2) * n / 2.5) if wire else 0.0
        return (srgb8(shade * 0.8), srgb8(shade * 0.82), srgb8(shade * 0.85), 255 if wire else 0)
    return png_bytes(n, n, image(n, n, px), 4)


def grass_texture(n=256, seed=3):
    rng = Rng(seed)
    vals = [rng.next() for _ in range(n * n)]
    def px(x, y):
        t = vals[y * n + x]
        return (srgb8(0.05 + 0.06 * t), srgb8(0.12 + 0.12 * t), srgb8(0.03 + 0.03 * t))
    return png_bytes(n, n, image(n, n, px), 3)


def brick_texture(n=512):
    """Bricks 64 x 32 texels with 4-texel mortar, staggered rows, per-brick tone."""
    rng = Rng(11)
    tones = [0.6 + 0.4 * rng.next() for _ in range(64 * 32)]
    def px(x, y):
        row = y // 32
        xs = x + (32 if row % 2 else 0)
        col = (xs // 64) % 8
        mortar = (y % 32) < 4 or (xs % 64) < 4
        if mortar:
            return (srgb8(0.55), srgb8(0.53), srgb8(0.5))
        t = tones[(row * 8 + col) % len(tones)]
        return (srgb8(0.45 * t), srgb8(0.14 * t), srgb8(0.08 * t))
    return png_bytes(n, n, image(n, n, px), 3)


def tile_texture(n=256):
    """Black/white floor tiles, 8 x 8 per texture, with 2-texel grout."""
    def px(x, y):
        c = ((x // 32) + (y // 32)) % 2
        grout = (x % 32) < 2 or (y % 32) < 2
        v = 0.35 if grout else (0.85 if c else 0.04)
        return (srgb8(v), srgb8(v), srgb8(v))
    return png_bytes(n, n, image(n, n, px), 3)


def bump_normal_texture(n=256, seed=5):
    """Tangent-space normals of a field of small round bumps (cones smoothed by cos)."""
    rng = Rng(seed)
    bumps = [(rng.next(), rng.next(), 0.02 + 0.03 * rng.next()) for _ in range(180)]
    h = [[0.0] * n for _ in range(n)]
    for (bx, by, r) in bumps:
        for y in range(int((by - r) * n) - 1, int((by + r) * n) + 2):
            for x in range(int((bx - r) * n) - 1, int((bx + r) * n) + 2):
                u, v = (x + 0.5) / n, (y + 0.5) / n
                d = math.hypot(u - bx, v - by) / r
                if d < 1.0:
                    h[y % n][x % n] += 0.5 * r * (1.0 + math.cos(math.pi * d))
    def px(x, y):
        dx = (h[y][(x + 1) % n] - h[y][(x - 1) % n]) * n / 2.0
        dy = (h[(y + 1) % n][x] - h[(y - 1) % n][x]) * n / 2.0
        nx, ny, nz = -dx * 1.5, dy * 1.5, 1.0
        l = math.sqrt(nx * nx + ny * ny + nz * nz)
        return (clamp8((nx / l + 1) / 2), clamp8((ny / l + 1) / 2), clamp8((nz / l + 1) / 2))
    return png_bytes(n, n, image(n, n, px), 3)


def roughness_texture(n=64):
    """metallicRoughness: G = roughness 0.5..1 (times the factor), B = metallic 0."""
    rng = Rng(9)
    vals = [rng.next() for _ in range(n * n)]
    return png_bytes(n, n, image(n, n, lambda x, y: (0, clamp8(0.5 + 0.5 * vals[y * n + x]), 0)), 3)


def facade_texture(n=256):
    """A facade of 8 x 8 windows: lit (warm) or dark panes in light frames."""
    rng = Rng(13)
    lit = [rng.next() < 0.35 for _ in range(64)]
    def px(x, y):
        cx, cy = x // 32, y // 32
        fx, fy = x % 32, y % 32
        if 6 <= fx < 26 and 8 <= fy < 26:
            return (srgb8(0.9), srgb8(0.7), srgb8(0.35)) if lit[cy * 8 + cx] else (srgb8(0.02), srgb8(0.03), srgb8(0.05))
        return (srgb8(0.4), srgb8(0.38), srgb8(0.35))
    return png_bytes(n, n, image(n, n, px), 3)


def sign_texture(w=256, h=64):
    """Signage: blocky high-contrast glyph strokes, 2-6 texels wide, on a dark panel."""
    rng = Rng(17)
    strokes = []
    x = 8
    while x < w - 16:
        gw = 10 + int(rng.next() * 10)
        for _ in range(3):
            sx = x + int(rng.next() * gw)
            sy = 10 + int(rng.next() * 30)
            horiz = rng.next() < 0.5
            strokes.append((sx, sy, gw if horiz else 3, 3 if horiz else 22))
        x += gw + 6
    def px(x, y):
        for (sx, sy, sw, sh) in strokes:
            if sx <= x < sx + sw and sy <= y < sy + sh:
                return (srgb8(1.0), srgb8(0.95), srgb8(0.8))
        return (srgb8(0.05), srgb8(0.08), srgb8(0.2))
    return png_bytes(w, h, image(w, h, px), 3)


# --------------------------------------------------------------------------- geometry
def quad(center, ax, ay, uv_scale=(1.0, 1.0)):
    """A rectangle centre ± ax ± ay; uv (0,0) at centre - ax + ay (top-left), v down."""
    c = center
    p = [[c[i] - ax[i] + ay[i] for i in range(3)], [c[i] + ax[i] + ay[i] for i in range(3)],
         [c[i] + ax[i] - ay[i] for i in range(3)], [c[i] - ax[i] - ay[i] for i in range(3)]]
    n = cross(ax, ay)
    ln = math.sqrt(sum(k * k for k in n))
    n = [k / ln for k in n]
    su, sv = uv_scale
    uv = [[0, 0], [su, 0], [su, sv], [0, sv]]
    return {"pos": p, "nrm": [n] * 4, "uv": uv, "idx": [0, 3, 2, 0, 2, 1]}  # counter-clockwise about ax x ay


def quad_tangents(geo, ax):
    """Adds glTF TANGENTs to a quad(): xyz along +u (= +ax), w = -1 because v grows along -ay,
    so the bitangent cross(normal, tangent) * w points along +v (glTF 2.0 3.7.2.1). The same
    frame aalab derives from the uvs when a file has none (scenes/tracer_gltf.cpp TangentAt)."""
    ln = math.sqrt(sum(k * k for k in ax))
    geo["tan"] = [[ax[0] / ln, ax[1] / ln, ax[2] / ln, -1.0]] * len(geo["pos"])
    return geo


def box(center, size):
    hx, hy, hz = size[0] / 2, size[1] / 2, size[2] / 2
    faces = [((hx, 0, 0), (0, 0, -hz), (0, hy, 0)), ((-hx, 0, 0), (0, 0, hz), (0, hy, 0)),
             ((0, hy, 0), (hx, 0, 0), (0, 0, -hz)), ((0, -hy, 0), (hx, 0, 0), (0, 0, hz)),
             ((0, 0, hz), (hx, 0, 0), (0, hy, 0)), ((0, 0, -hz), (-hx, 0, 0), (0, hy, 0))]
    parts = []
    for (o, ax, ay) in faces:
        parts.append(quad([center[i] + o[i] for i in range(3)], ax, ay))
    return merge(parts)


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def merge(parts):
    out = {"pos": [], "nrm": [], "uv": [], "idx": []}
    for p in parts:
        base = len(out["pos"])
        out["pos"] += p["pos"]
        out["nrm"] += p["nrm"]
        out["uv"] += p["uv"]
        out["idx"] += [base + i for i in p["idx"]]
    return out


def wire(a, b, radius, sides=6):
    """A thin prism along a -> b (the power lines): `sides` flat faces, no caps."""
    d = [b[i] - a[i] for i in range(3)]
    ld = math.sqrt(sum(k * k for k in d))
    t = [k / ld for k in d]
    up = [0, 1, 0] if abs(t[1]) < 0.9 else [1, 0, 0]
    u = cross(t, up)
    lu = math.sqrt(sum(k * k for k in u))
    u = [k / lu for k in u]
    v = cross(t, u)
    pos, nrm, uv, idx = [], [], [], []
    for k in range(sides):
        ang = 2 * math.pi * k / sides
        off = [radius * (math.cos(ang) * u[i] + math.sin(ang) * v[i]) for i in range(3)]
        n = [math.cos(ang) * u[i] + math.sin(ang) * v[i] for i in range(3)]
        pos += [[a[i] + off[i] for i in range(3)], [b[i] + off[i] for i in range(3)]]
        nrm += [n, n]
        uv += [[0, 0], [1, 0]]
    for k in range(sides):
        a0, b0, a1, b1 = 2 * k, 2 * k + 1, 2 * ((k + 1) % sides), 2 * ((k + 1) % sides) + 1
        idx += [a0, b0, b1, a0, b1, a1]
    return {"pos": pos, "nrm": nrm, "uv": uv, "idx": idx}


def sagging_wire(a, b, sag, radius, segments=24):
    parts = []
    pts = []
    for k in range(segments + 1):
        t = k / segments
        p = [a[i] + (b[i] - a[i]) * t for i in range(3)]
        p[1] -= sag * 4 * t * (1 - t)
        pts.append(p)
    for k in range(segments):
        parts.append(wire(pts[k], pts[k + 1], radius))
    return merge(parts)


# --------------------------------------------------------------------------- GLB writer
class Glb:
    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "aalab scripts/make_real_scenes.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                    "accessors": [], "bufferViews": [], "buffers": [], "images": [], "textures": [],
                    "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497},
                                 {"magFilter": 9729, "minFilter": 9987, "wrapS": 33071, "wrapT": 33071}]}

    def view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        off = len(self.bin)
        self.bin += data
        bv = {"buffer": 0, "byteOffset": off, "byteLength": len(data)}
        if target:
            bv["target"] = target
        self.doc["bufferViews"].append(bv)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, ctype, typ, ncomp, minmax=False):
        fmt = "<" + ("f" if ctype == 5126 else "I") * (len(values) * ncomp)
        flat = [c for v in values for c in (v if ncomp > 1 else [v])]
        bv = self.view(struct.pack(fmt, *flat), 34963 if ctype == 5125 else 34962)
        acc = {"bufferView": bv, "componentType": ctype, "count": len(values), "type": typ}
        if minmax:
            acc["min"] = [min(v[i] for v in values) for i in range(ncomp)]
            acc["max"] = [max(v[i] for v in values) for i in range(ncomp)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def texture(self, png, sampler=0):
        bv = self.view(png)
        self.doc["images"].append({"bufferView": bv, "mimeType": "image/png"})
        self.doc["textures"].append({"source": len(self.doc["images"]) - 1, "sampler": sampler})
        return len(self.doc["textures"]) - 1

    def material(self, m):
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def mesh(self, geo, material, name):
        pos = self.accessor(geo["pos"], 5126, "VEC3", 3, minmax=True)
        nrm = self.accessor(geo["nrm"], 5126, "VEC3", 3)
        uv = self.accessor(geo["uv"], 5126, "VEC2", 2)
        attributes = {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}
        if "tan" in geo:  # a normal-mapped mesh carries its tangent space (the validator asks for it)
            attributes["TANGENT"] = self.accessor(geo["tan"], 5126, "VEC4", 4)
        idx = self.accessor(geo["idx"], 5125, "SCALAR", 1)
        self.doc["meshes"].append({"name": name, "primitives": [
            {"attributes": attributes, "indices": idx, "material": material}]})
        self.doc["nodes"].append({"name": name, "mesh": len(self.doc["meshes"]) - 1})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def camera(self, position, look_at, yfov_deg):
        """A perspective camera node looking from position to look_at (up ~ +Y)."""
        f = [look_at[i] - position[i] for i in range(3)]
        lf = math.sqrt(sum(k * k for k in f))
        f = [k / lf for k in f]
        r = cross(f, [0, 1, 0])
        lr = math.sqrt(sum(k * k for k in r))
        r = [k / lr for k in r]
        u = cross(r, f)
        z = [-k for k in f]  # glTF cameras look down -Z
        m = [r[0], r[1], r[2], 0, u[0], u[1], u[2], 0, z[0], z[1], z[2], 0, position[0], position[1], position[2], 1]
        self.doc.setdefault("cameras", []).append({"type": "perspective", "perspective": {
            "yfov": math.radians(yfov_deg), "znear": 0.05}})
        self.doc["nodes"].append({"name": "camera", "camera": len(self.doc["cameras"]) - 1, "matrix": m})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def write(self, path):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["buffers"] = [{"byteLength": len(self.bin)}]
        doc = {k: v for k, v in self.doc.items() if v != []}
        js = json.dumps(doc, separators=(",", ":"), sort_keys=True).encode()
        while len(js) % 4:
            js += b" "
        total = 12 + 8 + len(js) + 8 + len(self.bin)
        out = struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(js), 0x4E4F534A) + js
        out += struct.pack("<II", len(self.bin), 0x004E4942) + bytes(self.bin)
        with open(path, "wb") as f:
            f.write(out)


def pbr(base_tex=None, factor=(1, 1, 1, 1), metallic=0.0, roughness=0.8, **extra):
    m = {"pbrMetallicRoughness": {"baseColorFactor": list(factor), "metallicFactor": metallic, "roughnessFactor": roughness},
         "doubleSided": True}
    if base_tex is not None:
        m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": base_tex}
    m.update(extra)
    return m


# --------------------------------------------------------------------------- scenes
SKY = [2.2, 2.6, 3.2]


def scene_json(name, description, effects, glb, camera=None, lights=None, ambient=None, background=None,
               display=None, animation=None):
    s = {"name": name, "description": description, "effects": effects,
         "camera": camera or {"type": "gltf", "index": 0}}
    if display:
        s["display"] = display
    if background:
        s["background"] = background
    if ambient:
        s["ambient"] = ambient
    s["materials"] = {}
    if lights:
        s["light_units"] = "gltf"
        s["lights"] = lights
    s["objects"] = [{"shape": "gltf", "file": glb}]
    if animation:
        s["animation"] = animation
    return s


def gltf_lux(legacy):
    """The glTF-unit literal (lux) of a sun stated in aalab's pre-2026-11 convention (pi times
    smaller): the shortest decimal of legacy * pi that aalab reads back to the same float
    (docs/lighting.md "Units"), so the scenes render with the same bits as before."""
    target = struct.unpack("f", struct.pack("f", legacy))[0]
    for digits in range(6, 18):
        text = "%.*g" % (digits, legacy * math.pi)
        if struct.unpack("f", struct.pack("f", float(text) / math.pi))[0] == target:
            return float(text)
    raise ValueError(legacy)


def sun(direction, intensity=2.5, shadows=False):
    return {"type": "directional", "direction": direction, "color": [1.0, 0.95, 0.85], "intensity": gltf_lux(intensity),
            "shadows": shadows}


ACES = {"exposure": 0.6, "tonemap": "aces"}


def make_foliage():
    g = Glb()
    leaf = g.texture(leaf_texture())
    grass = g.texture(grass_texture())
    mleaf = g.material(pbr(leaf, roughness=0.6, alphaMode="MASK", alphaCutoff=0.5, name="leaves"))
    mground = g.material(pbr(grass, roughness=0.9, name="ground"))
    g.mesh(quad([0, 0, -10], [30, 0, 0], [0, 0, 30], (40, 40)), mground, "ground")
    rng = Rng(21)
    cards = []
    for k in range(70):
        cx, cy, cz = -6 + 12 * rng.next(), 0.8 + 3.5 * rng.next(), -4 - 16 * rng.next()
        a = rng.next() * math.pi
        s = 0.6 + 0.8 * rng.next()
        ax = [s * math.cos(a), 0.15 * s * (rng.next() - 0.5), s * math.sin(a)]
        ay = [0.2 * s * (rng.next() - 0.5), s, 0.2 * s * (rng.next() - 0.5)]
        cards.append(quad([cx, cy, cz], ax, ay))
    g.mesh(merge(cards), mleaf, "leaf-cards")
    g.camera([0, 1.7, 3], [0, 2.2, -10], 50)
    g.write(os.path.join(GLB_DIR, "foliage.glb"))
    return scene_json("real-foliage", "alpha-tested leaf cards (MASK 0.5) over a grass texture under the sun: cut-out edges that mip-mapping thins with distance",
                      ["lambert", "specular", "textures", "alpha_test", "shadows"], "real/foliage.glb",
                      lights=[sun([0.4, -1.0, -0.5], 2.2, True)], ambient=[0.25, 0.3, 0.4], background=SKY, display=ACES)


def make_fence():
    g = Glb()
    link = g.texture(chainlink_texture())
    grass = g.texture(grass_texture(seed=4))
    mlink = g.material(pbr(link, metallic=0.8, roughness=0.45, alphaMode="MASK", alphaCutoff=0.5, name="chain-link"))
    mground = g.material(pbr(grass, roughness=0.9, name="ground"))
    mpost = g.material(pbr(None, (0.3, 0.3, 0.32, 1), metallic=0.9, roughness=0.4, name="posts"))
    g.mesh(quad([0, 0, -10], [30, 0, 0], [0, 0, 30], (40, 40)), mground, "ground")
    # The fence runs diagonally away from the camera: cells from ~6 px down to sub-pixel.
    start, end = [-2.5, 0, 1.0], [-1.0, 0, -40.0]
    d = [end[i] - start[i] for i in range(3)]
    length = math.sqrt(sum(k * k for k in d))
    ax = [d[i] / 2 for i in range(3)]
    centre = [start[i] + d[i] / 2 for i in range(3)]
    centre[1] = 1.0
    g.mesh(quad(centre, ax, [0, 1.0, 0], (length / 0.12, 2.0 / 0.12)), mlink, "fence")
    posts = []
    for k in range(0, 16):
        t = k / 15
        p = [start[i] + d[i] * t for i in range(3)]
        posts.append(box([p[0], 1.05, p[2]], [0.06, 2.1, 0.06]))
    g.mesh(merge(posts), mpost, "posts")
    g.camera([0.5, 1.5, 3.0], [-1.6, 1.2, -6], 55)
    g.write(os.path.join(GLB_DIR, "fence.glb"))
    return scene_json("real-fence", "a chain-link fence (MASK wire texture, 5-texel wires) running from near to far against a bright sky",
                      ["lambert", "specular", "textures", "alpha_test"], "real/fence.glb",
                      lights=[sun([-0.3, -1.0, -0.6], 2.0)], ambient=[0.3, 0.35, 0.45], background=[3.0, 3.3, 3.8], display=ACES)


def make_wires():
    g = Glb()
    mwire = g.material(pbr(None, (0.02, 0.02, 0.02, 1), metallic=0.0, roughness=0.5, name="cable"))
    mpole = g.material(pbr(None, (0.25, 0.18, 0.1, 1), roughness=0.8, name="poles"))
    mground = g.material(pbr(g.texture(grass_texture(seed=6)), roughness=0.9, name="ground"))
    g.mesh(quad([0, 0, -30], [80, 0, 0], [0, 0, 60], (60, 60)), mground, "ground")
    wires, poles = [], []
    xs = [-30, -10, 10, 30]
    for (x0, x1) in zip(xs, xs[1:]):
        for k, (h, z) in enumerate([(7.6, -25.0), (7.6, -24.4), (7.0, -24.7), (6.4, -25.3)]):
            wires.append(sagging_wire([x0, h, z - 0.02 * x0], [x1, h, z - 0.02 * x1], 0.8, 0.012))
    for x in xs:
        poles.append(box([x, 4.0, -24.9 - 0.02 * x], [0.3, 8.0, 0.3]))
        poles.append(box([x, 7.6, -24.9 - 0.02 * x], [0.15, 0.15, 1.6]))
    g.mesh(merge(wires), mwire, "cables")
    g.mesh(merge(poles), mpole, "poles")
    g.camera([0, 1.7, 5], [0, 5.0, -25], 45)
    g.write(os.path.join(GLB_DIR, "wires.glb"))
    return scene_json("real-wires", "power lines 2.4 cm thick 30 m away (0.2-0.5 px at 960x540) sagging against a bright sky",
                      ["lambert", "specular", "textures"], "real/wires.glb",
                      lights=[sun([0.2, -1.0, -0.4], 2.0)], ambient=[0.3, 0.35, 0.45], background=SKY, display=ACES)


def make_grazing():
    g = Glb()
    mfloor = g.material(pbr(g.texture(tile_texture()), roughness=0.7, name="tiles"))
    mwall = g.material(pbr(g.texture(brick_texture()), roughness=0.9, name="bricks"))
    g.mesh(quad([0, 0, -40], [6, 0, 0], [0, 0, 45], (3, 22.5)), mfloor, "floor")
    g.mesh(quad([-6, 3, -40], [0, 0, 45], [0, 3, 0], (22.5, 1.5)), mwall, "wall")
    g.camera([-2.0, 1.0, 3.5], [-1.2, 0.9, -20], 55)
    g.write(os.path.join(GLB_DIR, "grazing.glb"))
    return scene_json("real-grazing", "a tiled floor and a brick wall seen at grazing angles: mip selection, moire and over-blur",
                      ["lambert", "specular", "textures"], "real/grazing.glb",
                      lights=[sun([0.5, -0.8, -0.3], 2.2)], ambient=[0.3, 0.3, 0.35], background=[0.4, 0.45, 0.55])


def make_glossy():
    g = Glb()
    nrm = g.texture(bump_normal_texture())
    rough = g.texture(roughness_texture())
    mfloor = g.material(pbr(None, (0.05, 0.05, 0.06, 1), metallic=0.0, roughness=0.18, name="glossy-floor",
                            normalTexture={"index": nrm, "scale": 1.0}))
    mfloor_m = g.doc["materials"][mfloor]
    mfloor_m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {"index": rough}
    g.mesh(quad_tangents(quad([0, 0, -30], [30, 0, 0], [0, 0, 35], (12, 14)), [30, 0, 0]), mfloor, "floor")
    g.camera([0, 1.6, 4], [0, 0.2, -20], 50)
    g.write(os.path.join(GLB_DIR, "glossy.glb"))
    return scene_json("real-glossy", "a normal-mapped glossy floor (roughness 0.09-0.18) with the sun's highlight: specular aliasing",
                      ["lambert", "specular", "textures", "normal_map"], "real/glossy.glb",
                      lights=[sun([0.0, -0.35, 1.0], 6.0)], ambient=[0.08, 0.09, 0.12], background=[0.6, 0.7, 0.9], display=ACES)


def make_windows():
    g = Glb()
    mfacade = g.material(pbr(g.texture(facade_texture()), roughness=0.5, name="facade",
                             emissiveFactor=[0.0, 0.0, 0.0]))
    sign = g.texture(sign_texture(), sampler=1)
    msign = g.material(pbr(sign, roughness=0.5, name="sign", emissiveFactor=[1.0, 1.0, 1.0], emissiveTexture={"index": sign}))
    mground = g.material(pbr(None, (0.2, 0.2, 0.2, 1), roughness=0.9, name="street"))
    g.mesh(quad([0, 0, -60], [80, 0, 0], [0, 0, 70], (1, 1)), mground, "street")
    buildings = []
    rng = Rng(23)
    x = -60.0
    while x < 60.0:
        w = 10 + 8 * rng.next()
        h = 15 + 30 * rng.next()
        z = -70 - 20 * rng.next()
        floors, cols = h / 3.5, w / 3.0
        buildings.append(quad([x + w / 2, h / 2, z], [w / 2, 0, 0], [0, h / 2, 0], (cols / 8, floors / 8)))
        x += w + 2
    g.mesh(merge(buildings), mfacade, "facades")
    g.mesh(quad([6, 6, -40], [4, 0, 0], [0, 1, 0]), msign, "sign")
    g.camera([0, 1.7, 5], [0, 12, -70], 40)
    g.write(os.path.join(GLB_DIR, "windows.glb"))
    return scene_json("real-windows", "distant facades with window grids (windows 1-3 px) and an emissive sign: regular detail near the Nyquist limit",
                      ["lambert", "specular", "textures"], "real/windows.glb",
                      lights=[sun([0.3, -0.7, -0.6], 1.8)], ambient=[0.25, 0.27, 0.32], background=[0.5, 0.6, 0.8])


def make_engine():
    path = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
    s = scene_json("real-engine", "Khronos 2CylinderEngine (assimp-testmodels): hundreds of thin CAD parts, silhouettes and specular edges",
                   ["lambert", "specular"], path,
                   camera={"type": "perspective", "position": [-300, 250, 600], "look_at": [0, 0, 0], "fov_y": 40},
                   lights=[sun([0.4, -1.0, -0.6], 1.2)], ambient=[0.15, 0.15, 0.18], background=[0.55, 0.6, 0.7],
                   display=ACES)
    return s


def ibl_variant(scene, name, description):
    """The scene lit by aalab's studio environment instead of its sun and ambient."""
    out = {}
    for k, v in scene.items():
        if k in ("lights", "light_units", "ambient"):
            continue
        if k == "objects":
            out["environment"] = {"map": "studio", "intensity": 1.0}
        out[k] = v
    out["name"] = name
    out["description"] = description
    return out


def main():
    os.makedirs(GLB_DIR, exist_ok=True)
    glossy = make_glossy()
    glossy_ibl = ibl_variant(glossy, "real-glossy-ibl",
                             "the normal-mapped glossy floor (roughness 0.09-0.18) lit by the studio environment "
                             "(image-based lighting): specular aliasing of reflected softboxes")
    scenes = [make_foliage(), make_fence(), make_wires(), make_grazing(), glossy, glossy_ibl, make_windows(), make_engine()]
    # Moving versions for the motion suite: sub-pixel camera pans (64 frames).
    for base, offset in (("real-fence", [0.08, 0.0, 0.0]), ("real-glossy", [0.0, 0.0, -0.5]),
                         ("real-glossy-ibl", [0.0, 0.0, -0.5]), ("real-foliage", [0.12, 0.0, 0.0])):
        s = dict(next(x for x in scenes if x["name"] == base))
        s["name"] = base + "-pan"
        s["description"] = s["description"].split(":")[0] + ", under a slow camera pan (64 frames)"
        s["animation"] = {"frames": 64, "camera": [{"frame": 0}, {"frame": 63, "offset": offset}]}
        scenes.append(s)
    for s in scenes:
        with open(os.path.join(OUT_DIR, s["name"] + ".json"), "w") as f:
            f.write(json.dumps(s, indent=2) + "\n")
        print("wrote", s["name"])


if __name__ == "__main__":
    main()
