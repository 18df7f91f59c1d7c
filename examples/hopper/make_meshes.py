#!/usr/bin/env python3
"""Writes the STL meshes of the hopper example (ASCII STL, metres):

  meshes/silo_D<mm>.stl     a flat-bottomed square silo, 0.1 m wide and 0.15 m tall,
                            with a circular orifice of diameter D mm in the middle of
                            its floor (z = 0)
  meshes/orifice_D<mm>.stl  the orifice itself (a disc at z = 0): the face through which
                            fix massflow/mesh counts the discharge

usage: python3 make_meshes.py 25 35     (orifice diameters in mm)
"""
import math
import sys

HALF = 0.05     # half width of the silo
HEIGHT = 0.15   # silo height
SEG = 48        # segments of the orifice circle (a multiple of 8: the corners lie on rays)


def facet(f, a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    ln = math.sqrt(sum(x * x for x in n)) or 1.0
    f.write("  facet normal %.9e %.9e %.9e\n    outer loop\n" % tuple(x / ln for x in n))
    for p in (a, b, c):
        f.write("      vertex %.9e %.9e %.9e\n" % p)
    f.write("    endloop\n  endfacet\n")


def write(d_mm):
    r = d_mm / 2000.0
    ang = [2.0 * math.pi * k / SEG for k in range(SEG)]
    circle = [(r * math.cos(a), r * math.sin(a), 0.0) for a in ang]
    # The floor's outline, on the same rays as the circle (corners included).
    square = []
    for a in ang:
        c, s = math.cos(a), math.sin(a)
        m = HALF / max(abs(c), abs(s))
        square.append((round(m * c, 12), round(m * s, 12), 0.0))
    with open("meshes/silo_D%d.stl" % d_mm, "w") as f:
        f.write("solid silo\n")
        for k in range(SEG):
            j = (k + 1) % SEG
            facet(f, circle[k], square[k], square[j])
            facet(f, circle[k], square[j], circle[j])
        corners = [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)]
        for k in range(4):
            (x0, y0), (x1, y1) = corners[k], corners[(k + 1) % 4]
            a, b = (x0, y0, 0.0), (x1, y1, 0.0)
            c, d = (x1, y1, HEIGHT), (x0, y0, HEIGHT)
            facet(f, a, b, c)
            facet(f, a, c, d)
        f.write("endsolid silo\n")
    with open("meshes/orifice_D%d.stl" % d_mm, "w") as f:
        f.write("solid orifice\n")
        for k in range(SEG):
            facet(f, (0.0, 0.0, 0.0), circle[k], circle[(k + 1) % SEG])
        f.write("endsolid orifice\n")


if __name__ == "__main__":
    for arg in sys.argv[1:] or ["25", "35"]:
        write(int(arg))
