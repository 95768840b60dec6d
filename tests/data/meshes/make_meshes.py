#!/usr/bin/python3
"""Writes the small test meshes in this folder (run from anywhere; files land next to it).

Valid: box_ascii.stl, box_binary.stl (box 0.2 x 0.1 x 0.05 m centred at (1, 2, 3)),
cube_quads.obj (unit cube from quads, with i/t/n indices), tetra.obj, bent_leaf.obj (a curled
6 x 4 cm leaf 0.4 mm thick, 1696 triangles, turned 20 degrees about z: an artist's leaf, whose
generalized mass is a full 6 x 6; tests/support/batch_compare.h bent_leaf builds the same),
leaf_surface.obj (the mid-surface of that leaf alone, open and single-sided, in quads with UVs
and a normal, as Blender exports a leaf: a body with a "thickness").
Invalid (each has exactly one defect): open.obj, nonmanifold_edge.obj, nonmanifold_vertex.obj,
inverted.obj, inconsistent.obj, degenerate.obj; syntax errors: bad_number.obj,
bad_index.obj, truncated.stl.
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def box(lx, ly, lz, c):
    """8 corners and 12 outward triangles (counter-clockwise seen from outside)."""
    v = [(c[0] + sx * lx / 2, c[1] + sy * ly / 2, c[2] + sz * lz / 2)
         for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    # corner index = 4*ix + 2*iy + iz
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    f = []
    for a, b, cc, d in quads:
        f += [(a, b, cc), (a, cc, d)]
    return v, f, quads


def write_obj(name, v, f, comment):
    with open(os.path.join(HERE, name), "w") as out:
        out.write("# %s\n" % comment)
        for p in v:
            out.write("v %.17g %.17g %.17g\n" % p)
        for t in f:
            out.write("f " + " ".join(str(i + 1) for i in t) + "\n")


def normal(v, t):
    a, b, c = (v[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    s = sum(x * x for x in n) ** 0.5
    return [x / s for x in n]


def bent_leaf(nx=25, ny=17, length=0.06, width=0.04, thick=4e-4, sag=0.004, yaw_deg=20.0):
    """A plate bent about its width: mid-surface z = sag (2x/length)^2, thickness along the
    normal, turned by yaw about z. Top and bottom grids of nx x ny vertices, the rim closed by
    side strips: 4 (nx - 1)(ny - 1) + 4 (nx + ny - 2) outward triangles (1696 by default)."""
    import math
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    v = []
    for side in (1, -1):  # top, then bottom
        for i in range(nx):
            for j in range(ny):
                x = -length / 2 + length * i / (nx - 1)
                y = -width / 2 + width * j / (ny - 1)
                z = sag * (2 * x / length) ** 2
                dz = 8 * sag * x / length ** 2
                n = math.sqrt(1 + dz * dz)
                px, pz = x - side * 0.5 * thick * dz / n, z + side * 0.5 * thick / n
                v.append((c * px - s * y, s * px + c * y, pz))
    T = lambda i, j: i * ny + j
    B = lambda i, j: nx * ny + i * ny + j
    f = []
    for i in range(nx - 1):
        for j in range(ny - 1):
            a, b, cc, d = (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)
            f += [(T(*a), T(*b), T(*cc)), (T(*a), T(*cc), T(*d))]
            f += [(B(*a), B(*cc), B(*b)), (B(*a), B(*d), B(*cc))]
    # the rim, counter-clockwise seen from +z
    rim = ([(i, 0) for i in range(nx)] + [(nx - 1, j) for j in range(1, ny)] +
           [(i, ny - 1) for i in range(nx - 2, -1, -1)] + [(0, j) for j in range(ny - 2, 0, -1)])
    for k in range(len(rim)):
        p, q = rim[k], rim[(k + 1) % len(rim)]
        f += [(B(*p), B(*q), T(*q)), (B(*p), T(*q), T(*p))]
    return v, f


def leaf_surface(nx=25, ny=17, length=0.06, width=0.04, sag=0.004, yaw_deg=20.0):
    """The mid-surface of bent_leaf: nx x ny vertices, (nx - 1)(ny - 1) quads wound
    counter-clockwise seen from +z, UVs (i / (nx - 1), j / (ny - 1))."""
    import math
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    v, uv = [], []
    for i in range(nx):
        for j in range(ny):
            x = -length / 2 + length * i / (nx - 1)
            y = -width / 2 + width * j / (ny - 1)
            z = sag * (2 * x / length) ** 2
            v.append((c * x - s * y, s * x + c * y, z))
            uv.append((i / (nx - 1), j / (ny - 1)))
    quads = [(i * ny + j, (i + 1) * ny + j, (i + 1) * ny + j + 1, i * ny + j + 1)
             for i in range(nx - 1) for j in range(ny - 1)]
    return v, uv, quads


def main():
    v, f, quads = box(0.2, 0.1, 0.05, (1.0, 2.0, 3.0))
    with open(os.path.join(HERE, "box_ascii.stl"), "w") as out:
        out.write("solid box\n")
        for t in f:
            out.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % tuple(normal(v, t)))
            for i in t:
                out.write("      vertex %.17g %.17g %.17g\n" % v[i])
            out.write("    endloop\n  endfacet\n")
        out.write("endsolid box\n")
    with open(os.path.join(HERE, "box_binary.stl"), "wb") as out:
        header = b"solid-looking header of a binary STL (must still be read as binary)"
        out.write(header.ljust(80, b" "))
        out.write(struct.pack("<I", len(f)))
        for t in f:
            out.write(struct.pack("<3f", *normal(v, t)))
            for i in t:
                out.write(struct.pack("<3f", *v[i]))
            out.write(struct.pack("<H", 0))

    # unit cube [0,1]^3 written with quads and v/vt/vn style indices
    cv, _, cq = box(1.0, 1.0, 1.0, (0.5, 0.5, 0.5))
    with open(os.path.join(HERE, "cube_quads.obj"), "w") as out:
        out.write("# unit cube [0,1]^3, quads, with texture/normal indices\no cube\n")
        for p in cv:
            out.write("v %g %g %g\n" % p)
        out.write("vt 0 0\nvn 0 0 1\ns off\n")
        for q in cq:
            out.write("f " + " ".join("%d/1/1" % (i + 1) for i in q) + "\n")

    sv, suv, sq = leaf_surface()
    with open(os.path.join(HERE, "leaf_surface.obj"), "w") as out:
        out.write("# mid-surface of bent_leaf.obj, open and single-sided, quads with UVs "
                  "(make_meshes.py leaf_surface), m\nmtllib leaf.mtl\no Leaf\n")
        for p in sv:
            out.write("v %.17g %.17g %.17g\n" % p)
        for t in suv:
            out.write("vt %.6f %.6f\n" % t)
        out.write("vn 0 0 1\ns 1\nusemtl leaf\n")
        for q in sq:
            out.write("f " + " ".join("%d/%d/1" % (i + 1, i + 1) for i in q) + "\n")

    lv, lf = bent_leaf()
    write_obj("bent_leaf.obj", lv, lf, "leaf 6 x 4 cm, 0.4 mm, curled 4 mm, turned 20 deg about z "
              "(make_meshes.py bent_leaf), m")

    tv = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    tf = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    write_obj("tetra.obj", tv, tf, "tetrahedron with corner at the origin, volume 1/6 m^3")

    write_obj("open.obj", v, f[:-1], "box with one triangle missing")
    write_obj("inverted.obj", v, [(a, c, b) for a, b, c in f], "box with every face reversed")
    write_obj("inconsistent.obj", v, f[:-1] + [tuple(reversed(f[-1]))], "box, one face flipped")

    # two tetrahedra sharing the edge 0-1: that edge has four faces
    nv = tv + [(0.5, -1, -1), (0.5, -1.2, 0.2)]
    nf = tf + [(0, 1, 4), (1, 0, 5), (0, 4, 5), (1, 5, 4)]
    write_obj("nonmanifold_edge.obj", nv, nf, "two tetrahedra sharing an edge")

    # two tetrahedra sharing only vertex 0 (a bow-tie vertex)
    bv = tv + [(-1, 0, 0), (0, -1, 0), (0, 0, -1)]
    bf = tf + [(0, 4, 5), (0, 6, 4), (0, 5, 6), (4, 6, 5)]
    write_obj("nonmanifold_vertex.obj", bv, bf, "two tetrahedra sharing a vertex")

    # tetrahedron with a midpoint M on edge A-B: faces AMC, MBC, BAD, ACD... plus a
    # zero-area face (A, B, M) that closes the surface
    A, B, C, D = (0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)
    M = (0.5, 0, 0)
    dv = [A, B, C, D, M]
    # original outward faces: (A, C, B), (A, B, D), (A, D, C), (B, C, D); split ACB at M
    df = [(0, 2, 4), (4, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3), (0, 4, 1)]
    write_obj("degenerate.obj", dv, df, "closed tetrahedron with one zero-area face")

    with open(os.path.join(HERE, "bad_number.obj"), "w") as out:
        out.write("# line 3 has a bad coordinate\nv 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n")
    with open(os.path.join(HERE, "bad_index.obj"), "w") as out:
        out.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with open(os.path.join(HERE, "truncated.stl"), "w") as out:
        out.write("solid t\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n"
                  "      vertex 1 0 0\n")


if __name__ == "__main__":
    main()
