"""Triangulated geometry for foamWindCase: reading STL/OBJ, the Y-up/scale transforms, the
checks a wind case needs (closed, manifold, consistently and outward oriented, sized), and an
ASCII STL writer. Standard library only.

Every error is a GeometryError whose message names the file and says what is wrong and where
(coordinates in metres after --up/--scale).
"""

import math
import os
import re
import struct


class GeometryError(Exception):
    """bad geometry: the message names the file and the problem"""


# ----------------------------------------------------------------------------- reading

def _read_stl_binary(data, path):
    if len(data) < 84:
        return None
    n = struct.unpack_from('<I', data, 80)[0]
    if 84 + 50 * n != len(data):
        return None
    tris = []
    for i in range(n):
        v = struct.unpack_from('<12f', data, 84 + 50 * i)
        tris.append(((v[3], v[4], v[5]), (v[6], v[7], v[8]), (v[9], v[10], v[11])))
    return tris


def _point(w, path, lineno, line, extra=False):
    """the 3 coordinates after the keyword w[0] of a vertex line (extra: more values may
    follow, as OBJ's optional w or the vertex colours some exporters write)"""
    if len(w) < 4 or (len(w) > 4 and not extra):
        raise GeometryError('%s:%d: a vertex needs 3 coordinates: "%s"'
                            % (path, lineno, line.strip()))
    try:
        return tuple(float(x) for x in w[1:4])
    except ValueError:
        raise GeometryError('%s:%d: not a number in "%s"' % (path, lineno, line.strip()))


def _read_stl_ascii(text, path):
    tris, loop = [], []
    for lineno, line in enumerate(text.splitlines(), 1):
        w = line.split()
        if not w:
            continue
        if w[0] == 'vertex':
            loop.append(_point(w, path, lineno, line))
        elif w[0] == 'endloop':
            if len(loop) != 3:
                raise GeometryError('%s:%d: a facet has %d vertices, STL needs 3'
                                    % (path, lineno, len(loop)))
            tris.append(tuple(loop))
            loop = []
        elif w[0] not in ('solid', 'endsolid', 'facet', 'outer', 'endfacet'):
            raise GeometryError('%s:%d: not an STL file (unexpected "%s")' % (path, lineno, w[0]))
    return tris


def _read_obj(text, path):
    verts, tris = [], []
    for lineno, line in enumerate(text.splitlines(), 1):
        w = line.split()
        if not w or w[0].startswith('#'):
            continue
        if w[0] == 'v':
            verts.append(_point(w, path, lineno, line, extra=True))
        elif w[0] == 'f':
            idx = []
            for tok in w[1:]:
                try:
                    i = int(tok.split('/')[0])
                except ValueError:
                    raise GeometryError('%s:%d: bad face index "%s"' % (path, lineno, tok))
                i = i - 1 if i > 0 else len(verts) + i
                if not 0 <= i < len(verts):
                    raise GeometryError('%s:%d: face index %s refers to no vertex (%d defined)'
                                        % (path, lineno, tok, len(verts)))
                idx.append(i)
            if len(idx) < 3:
                raise GeometryError('%s:%d: a face needs at least 3 vertices' % (path, lineno))
            for k in range(1, len(idx) - 1):   # fan: fine for the convex faces exporters write
                tris.append((verts[idx[0]], verts[idx[k]], verts[idx[k + 1]]))
        elif w[0] in ('vn', 'vt', 'vp', 'o', 'g', 's', 'usemtl', 'mtllib', 'l'):
            pass
        else:
            raise GeometryError('%s:%d: not an OBJ file (unexpected "%s")' % (path, lineno, w[0]))
    return tris


def read_surface(path):
    """triangles [(p0, p1, p2), ...] of an STL (ascii or binary) or OBJ file"""
    if not os.path.isfile(path):
        raise GeometryError('%s: no such file' % path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in ('.stl', '.obj'):
        raise GeometryError('%s: unknown extension "%s": give an .stl or .obj file' % (path, ext))
    with open(path, 'rb') as f:
        data = f.read()
    if not data.strip():
        raise GeometryError('%s: the file is empty' % path)
    tris = None
    if ext == '.stl':
        tris = _read_stl_binary(data, path)
        if tris is None:
            try:
                text = data.decode('ascii')
            except UnicodeDecodeError:
                raise GeometryError('%s: not a mesh: neither ASCII STL nor binary STL (size %d '
                                    'bytes does not match a triangle count)' % (path, len(data)))
            tris = _read_stl_ascii(text, path)
    else:
        try:
            text = data.decode('utf-8')
        except UnicodeDecodeError:
            raise GeometryError('%s: not a mesh: an OBJ file must be text' % path)
        tris = _read_obj(text, path)
    if not tris:
        raise GeometryError('%s: not a mesh: no triangles in the file' % path)
    for t in tris:
        for p in t:
            if not all(math.isfinite(c) for c in p):
                raise GeometryError('%s: a vertex has a non-finite coordinate %s' % (path, p))
    return tris


# ----------------------------------------------------------------------------- transforms

def transform(tris, up='z', scale=1.0):
    """Z-up metres. up='y': the file is Y-up (Blender's OBJ export: file (x, y, z) is
    Blender (x, -z, y)), mapped to (x, -z, y); then every coordinate times scale"""
    def f(p):
        x, y, z = p
        if up == 'y':
            x, y, z = x, -z, y
        return (x * scale, y * scale, z * scale)
    return [tuple(f(p) for p in t) for t in tris]


# ----------------------------------------------------------------------------- checks

def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _fmt(p):
    return '(%.4g %.4g %.4g)' % p


def bounds(tris):
    lo = [min(p[i] for t in tris for p in t) for i in range(3)]
    hi = [max(p[i] for t in tris for p in t) for i in range(3)]
    return lo, hi


def check_closed_oriented(tris, path):
    """Weld the vertices, then: no degenerate triangles, every edge shared by exactly two
    triangles that run through it in opposite directions (closed, manifold, consistently
    oriented), and every connected part encloses a positive volume (normals outward).
    Returns (number of parts, total volume m^3)."""
    lo, hi = bounds(tris)
    diag = math.sqrt(sum((h - l) ** 2 for l, h in zip(lo, hi)))
    if diag == 0:
        raise GeometryError('%s: all vertices are at one point %s' % (path, _fmt(tuple(lo))))
    tol = 1e-7 * diag
    ids, pts, faces = {}, [], []
    for t in tris:
        f = []
        for p in t:
            key = tuple(int(round(c / tol)) for c in p)
            if key not in ids:
                ids[key] = len(pts)
                pts.append(p)
            f.append(ids[key])
        faces.append(f)
    # degenerate triangles (zero area): report, they break every later step
    for fi, (a, b, c) in enumerate(faces):
        n = _cross(_sub(pts[b], pts[a]), _sub(pts[c], pts[a]))
        if a == b or b == c or a == c or math.sqrt(sum(x * x for x in n)) <= (tol * diag):
            raise GeometryError('%s: triangle %d has zero area (at %s)'
                                % (path, fi + 1, _fmt(pts[a])))
    # directed edges
    directed = {}
    for fi, f in enumerate(faces):
        for k in range(3):
            e = (f[k], f[(k + 1) % 3])
            directed.setdefault(e, []).append(fi)
    undirected = {}
    for (a, b), fl in directed.items():
        undirected.setdefault((min(a, b), max(a, b)), []).extend(fl)

    def where(edges):
        shown = ', '.join('%s-%s' % (_fmt(pts[a]), _fmt(pts[b])) for a, b in edges[:3])
        more = ' and %d more' % (len(edges) - 3) if len(edges) > 3 else ''
        return shown + more

    open_edges = sorted(e for e, fl in undirected.items() if len(fl) == 1)
    nonmanifold = sorted(e for e, fl in undirected.items() if len(fl) > 2)
    if nonmanifold:
        raise GeometryError('%s: not manifold: %d edges are shared by more than two triangles, '
                            'e.g. the edge %s (split touching parts or merge them into one '
                            'closed body)' % (path, len(nonmanifold), where(nonmanifold)))
    if open_edges:
        raise GeometryError('%s: the surface is open: %d edges belong to one triangle only '
                            '(a hole), e.g. the edge %s (close the hole; a building needs its '
                            'floor too)' % (path, len(open_edges), where(open_edges)))
    flipped = sorted((min(a, b), max(a, b)) for (a, b), fl in directed.items()
                     if len(fl) > 1 and a < b)
    if flipped:
        raise GeometryError('%s: inconsistent orientation: %d edges are run through in the '
                            'same direction by both of their triangles (some normals point '
                            'the other way), e.g. the edge %s (recalculate the normals '
                            'outside before exporting)' % (path, len(flipped), where(flipped)))
    # connected parts (through shared edges) and their enclosed volumes
    parent = list(range(len(faces)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    for fl in undirected.values():
        r0 = find(fl[0])
        for fi in fl[1:]:
            r = find(fi)
            if r != r0:
                parent[r] = r0
    vol = {}
    for fi, (a, b, c) in enumerate(faces):
        pa, pb, pc = pts[a], pts[b], pts[c]
        v = (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1]) - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0])
             + pa[2] * (pb[0] * pc[1] - pb[1] * pc[0])) / 6.0
        r = find(fi)
        vol[r] = vol.get(r, 0.0) + v
    for r, v in vol.items():
        a = faces[r][0]
        if v < 0:
            raise GeometryError('%s: inverted: the part that contains the point %s has its '
                                'normals pointing inwards (volume %.4g m^3); flip its normals'
                                % (path, _fmt(pts[a]), v))
        if v <= 1e-12 * diag ** 3:
            raise GeometryError('%s: the part that contains the point %s encloses no volume '
                                '(a flat sheet?)' % (path, _fmt(pts[a])))
    return len(vol), sum(vol.values())


# ----------------------------------------------------------------------------- writing

def write_stl(tris, path, name='geometry'):
    """ASCII STL (OpenFOAM reads it; normals from the vertex order)"""
    with open(path, 'w') as f:
        f.write('solid %s\n' % name)
        for t in tris:
            n = _cross(_sub(t[1], t[0]), _sub(t[2], t[0]))
            ln = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write('  facet normal %.9g %.9g %.9g\n    outer loop\n' % tuple(x / ln for x in n))
            for p in t:
                f.write('      vertex %.9g %.9g %.9g\n' % p)
            f.write('    endloop\n  endfacet\n')
        f.write('endsolid %s\n' % name)


def write_obj_yup(tris, path):
    """OBJ with Y up, as Blender exports it: Z-up (x, y, z) is written as (x, z, -y)"""
    ids, pts, faces = {}, [], []
    for t in tris:
        f = []
        for p in t:
            if p not in ids:
                ids[p] = len(pts) + 1
                pts.append(p)
            f.append(ids[p])
        faces.append(f)
    with open(path, 'w') as out:
        out.write('# Y-up OBJ (as exported by Blender: forward -Z, up Y)\n')
        for x, y, z in pts:
            out.write('v %.9g %.9g %.9g\n' % (x, z, -y))
        for f in faces:
            out.write('f %d %d %d\n' % tuple(f))


SELF_INTERSECT_RE = re.compile(r'[Ss]urface is self-intersecting')
