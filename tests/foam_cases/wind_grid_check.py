#!/usr/bin/python3
"""Checks of the grids foamWindCase writes (tests/foam_cases, label foam). VTK + numpy.

  wind_grid_check.py inside CASE_DIR
      grid points inside the geometry (constant/triSurface/geometry.stl) by more than the
      finest cell are all invalid (valid = 0); points farther than two finest cells outside
      it are valid (>= 99 %); prints the counts. The grid's wall_distance (foam2grid) agrees
      with the distance to the geometry or the ground, whichever is nearer (VTK's
      vtkImplicitPolyDataDistance to the STL, computed here independently) within 1.5 finest
      cells wherever the snapped mesh and the STL can differ, and has the validity's sign
  wind_grid_check.py loglaw CASE_DIR
      the mean-flow profile 1 H downstream of the inlet, on the domain's centre line, at
      0.5 H, 1 H and 2 H above the ground: |U| within 5 % of the log law
      u*/kappa ln((z + z0)/z0) (u* from Uref at Zref), read from windCase.json
  wind_grid_check.py recirculation CASE_DIR LO HI
      behind a cube (direction 0): the along-wind velocity on the centre line 0.1 H above
      the ground changes sign at X_R behind the leeward face; X_R/H must lie in [LO, HI]
  wind_grid_check.py same A.vti B.vti TOL
      the two grids have the same dimensions, origin, spacing and valid mask, and every field
      agrees to TOL of its largest magnitude
Exit 0 when the check passes, 1 with a message otherwise.
"""

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def fail(msg):
    print('FAIL: ' + msg)
    sys.exit(1)


def read_vti(path):
    r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    if img.GetNumberOfPoints() == 0:
        fail('%s: no grid points' % path)
    return img


def arrays(img):
    pd = img.GetPointData()
    return {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}


def points(img):
    n = img.GetDimensions()
    o = np.array(img.GetOrigin())
    h = np.array(img.GetSpacing())
    i, j, k = np.meshgrid(np.arange(n[0]), np.arange(n[1]), np.arange(n[2]), indexing='ij')
    # VTK order: x fastest
    idx = np.stack([i.ravel(order='F'), j.ravel(order='F'), k.ravel(order='F')], axis=1)
    return o + idx * h


def info(case):
    return json.load(open(os.path.join(case, 'windCase.json')))


def check_inside(case):
    w = info(case)
    img = read_vti(os.path.join(case, w['grid']))
    valid = arrays(img)['valid']
    pts = points(img)
    stl = vtk.vtkSTLReader()
    stl.SetFileName(os.path.join(case, 'constant', 'triSurface', 'geometry.stl'))
    stl.Update()
    surf = stl.GetOutput()
    # signed distance to the surface (negative inside)
    dist = vtk.vtkImplicitPolyDataDistance()
    dist.SetInput(surf)
    d = np.array([dist.EvaluateFunction(p) for p in pts])
    h = w['finest_cell']
    inside = d < -h
    outside = d > 2 * h
    # within the fluid only above the ground
    above = pts[:, 2] > w['ground'] + h
    n_in = int(inside.sum())
    if n_in == 0:
        fail('no grid point lies inside the geometry by more than %g m' % h)
    bad_in = int((valid[inside] != 0).sum())
    out_sel = outside & above
    frac_out = float((valid[out_sel] != 0).mean())
    print('inside the geometry (deeper than %.3g m): %d points, %d of them valid' % (h, n_in, bad_in))
    print('outside (farther than %.3g m, above the ground): %d points, %.4f valid'
          % (2 * h, int(out_sel.sum()), frac_out))
    if bad_in:
        fail('%d grid points inside the geometry are marked valid' % bad_in)
    if frac_out < 0.99:
        fail('only %.4f of the points outside the geometry are valid (want >= 0.99)' % frac_out)
    check_wall_distance(img, pts, d, w)


def check_wall_distance(img, pts, d_stl, w):
    a = arrays(img)
    if 'wall_distance' not in a:
        fail('the grid has no wall_distance array')
    wd = a['wall_distance'].astype(float)
    valid = a['valid']
    h = w['finest_cell']
    # the walls: the geometry (snapped onto the mesh within about a cell) and the ground
    height = pts[:, 2] - w['ground']
    want = np.where(d_stl > 0, np.minimum(d_stl, height), d_stl)
    wrong = np.signbit(wd) != (valid == 0)  # -0.0 on a wall counts as inside
    if wrong.any():
        fail('wall_distance has the wrong sign at %d points' % int(wrong.sum()))
    # inside the geometry, under the ground plane's level, the ground has no face: only compare
    # inside points deeper than their height above the ground's level
    sel = (d_stl > 0) | (-d_stl < height)
    err = np.abs(wd - want)[sel]
    print('wall_distance vs the STL and the ground: max |difference| %.3g m over %d points '
          '(finest cell %.3g m)' % (err.max(), int(sel.sum()), h))
    if err.max() > 1.5 * h:
        worst = np.argmax(np.abs(wd - want) * sel)
        fail('wall_distance %.4g m at %s, expected %.4g m (STL and ground) within %.3g m'
             % (wd[worst], pts[worst], want[worst], 1.5 * h))


def foam2grid_box(case, bounds, spacing):
    f2g = os.environ.get('FOAM2GRID', 'foam2grid')
    out = tempfile.mkdtemp(prefix='windcheck')
    vti = os.path.join(out, 'probe.vti')
    cmd = [f2g, case, '-o', vti, '--spacing', '%g' % spacing, '--bounds'] + \
          ['%.6g' % b for b in bounds] + ['-q']
    r = subprocess.run(cmd)
    if r.returncode != 0:
        fail('%s failed' % ' '.join(cmd))
    return read_vti(vti)


def check_loglaw(case):
    w = info(case)
    H, zg, z0 = w['H'], w['ground'], w['z0']
    ustar = 0.41 * w['speed'] / math.log((w['zref'] + z0) / z0)
    c = np.array(w['domain_corners'])
    d = np.array(w['flow_dir'])
    # 1 H downstream of the inlet centre (the inlet face is corners 0, 3, 4, 7)
    inlet_mid = 0.5 * (c[0] + c[3])
    p = inlet_mid + H * d
    heights = [0.5 * H, 1.0 * H, 2.0 * H]
    s = 0.05 * H
    bounds = [p[0] - s, p[0] + s, p[1] - s, p[1] + s, zg, zg + 2.0 * H + s]
    img = foam2grid_box(case, bounds, s)
    U = arrays(img)['U']
    pts = points(img)
    worst = 0.0
    for z in heights:
        sel = np.argmin(np.abs(pts[:, 0] - p[0]) + np.abs(pts[:, 1] - p[1])
                        + np.abs(pts[:, 2] - (zg + z)))
        zz = pts[sel, 2] - zg
        u = float(np.linalg.norm(U[sel]))
        ulog = ustar / 0.41 * math.log((zz + z0) / z0)
        err = abs(u - ulog) / ulog
        worst = max(worst, err)
        print('z = %.3g m above the ground: |U| = %.4g m/s, log law %.4g m/s, error %.2f %%'
              % (zz, u, ulog, 100 * err))
    if worst > 0.05:
        fail('inlet profile differs from the log law by %.2f %% (> 5 %%)' % (100 * worst))


def check_recirculation(case, lo, hi):
    w = info(case)
    H, zg = w['H'], w['ground']
    if abs(w['direction_deg']) > 1e-9:
        fail('the recirculation check needs --direction 0')
    xb = w['bounds_max'][0]        # leeward face
    yc = 0.5 * (w['bounds_min'][1] + w['bounds_max'][1])
    s = 0.02 * H
    z = zg + 0.1 * H
    bounds = [xb + s, xb + 6 * H, yc - s, yc + s, z - s, z + s]
    img = foam2grid_box(case, bounds, s)
    U = arrays(img)['U']
    valid = arrays(img)['valid']
    pts = points(img)
    sel = (np.abs(pts[:, 1] - yc) < 0.5 * s) & (np.abs(pts[:, 2] - z) < 0.5 * s) & (valid != 0)
    x = pts[sel, 0]
    ux = U[sel, 0]
    order = np.argsort(x)
    x, ux = x[order], ux[order]
    if len(x) < 10:
        fail('too few valid points behind the cube (%d)' % len(x))
    if ux[0] >= 0:
        fail('no reverse flow just behind the cube (Ux = %.3g m/s at %.3g H)'
             % (ux[0], (x[0] - xb) / H))
    k = np.nonzero(ux >= 0)[0]
    if len(k) == 0:
        fail('the flow does not reattach within 6 H behind the cube')
    i = k[0]
    xr = x[i - 1] + (x[i] - x[i - 1]) * (-ux[i - 1]) / (ux[i] - ux[i - 1])
    L = (xr - xb) / H
    print('recirculation length behind the cube (Ux = 0 at %.3g H above the ground on the '
          'centre line): X_R = %.3f m = %.3f H (accepted %.2f..%.2f H)' % (0.1, xr - xb, L, lo, hi))
    if not lo <= L <= hi:
        fail('X_R/H = %.3f outside [%.2f, %.2f]' % (L, lo, hi))


def check_same(a, b, tol):
    A, B = read_vti(a), read_vti(b)
    if A.GetDimensions() != B.GetDimensions():
        fail('dimensions differ: %s vs %s' % (A.GetDimensions(), B.GetDimensions()))
    if not np.allclose(A.GetOrigin(), B.GetOrigin(), atol=1e-6) or \
            not np.allclose(A.GetSpacing(), B.GetSpacing(), rtol=1e-9):
        fail('origin or spacing differ: %s %s vs %s %s' % (A.GetOrigin(), A.GetSpacing(),
                                                          B.GetOrigin(), B.GetSpacing()))
    fa, fb = arrays(A), arrays(B)
    if set(fa) != set(fb):
        fail('fields differ: %s vs %s' % (sorted(fa), sorted(fb)))
    nv = int((fa['valid'] != fb['valid']).sum())
    print('valid mask: %d of %d points differ' % (nv, len(fa['valid'])))
    if nv:
        fail('%d points differ in the valid mask' % nv)
    for name in sorted(fa):
        if name == 'valid':
            continue
        scale = float(np.abs(fa[name]).max()) or 1.0
        diff = float(np.abs(fa[name].astype(float) - fb[name].astype(float)).max()) / scale
        print('%s: max |A - B| / max |A| = %.3g' % (name, diff))
        if diff > tol:
            fail('%s differs by %.3g of its largest magnitude (> %g)' % (name, diff, tol))


def main(argv):
    if not argv:
        print(__doc__)
        return 2
    if argv[0] == 'inside':
        check_inside(argv[1])
    elif argv[0] == 'loglaw':
        check_loglaw(argv[1])
    elif argv[0] == 'recirculation':
        check_recirculation(argv[1], float(argv[2]), float(argv[3]))
    elif argv[0] == 'same':
        check_same(argv[1], argv[2], float(argv[3]))
    else:
        print(__doc__)
        return 2
    print('passed')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
