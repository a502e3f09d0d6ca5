#!/usr/bin/env python3
"""Writes scenes/library/meshes/torus-knot.obj: a (2,3) torus knot tube, flat-shaded
(no normals), coarse enough that its facets and silhouette give many geometric edges."""
import math, sys

P, Q = 2, 3
SEG, SIDES = 160, 10
R, r, TUBE = 1.6, 0.6, 0.32

def knot(t):
    c = R + r * math.cos(Q * t)
    return (c * math.cos(P * t), c * math.sin(P * t), r * math.sin(Q * t))

def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
def norm(a):
    l = math.sqrt(sum(x*x for x in a)); return tuple(x / l for x in a)

out = sys.argv[1] if len(sys.argv) > 1 else "scenes/library/meshes/torus-knot.obj"
verts = []
for i in range(SEG):
    t = 2 * math.pi * i / SEG
    p, q = knot(t), knot(t + 1e-3)
    tangent = norm(sub(q, p))
    n = norm(cross(tangent, (0.0, 0.0, 1.0)))
    b = cross(tangent, n)
    for j in range(SIDES):
        a = 2 * math.pi * j / SIDES
        verts.append(tuple(p[k] + TUBE * (math.cos(a) * n[k] + math.sin(a) * b[k]) for k in range(3)))
with open(out, "w") as f:
    f.write("# (2,3) torus knot tube, %d x %d quads as triangles; made by scripts/make_torus_knot.py\n" % (SEG, SIDES))
    for v in verts:
        f.write("v %.6f %.6f %.6f\n" % v)
    for i in range(SEG):
        for j in range(SIDES):
            a = i * SIDES + j + 1
            b = i * SIDES + (j + 1) % SIDES + 1
            c = ((i + 1) % SEG) * SIDES + (j + 1) % SIDES + 1
            d = ((i + 1) % SEG) * SIDES + j + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (a, b, c, a, c, d))
