"""Grid.load + vectorised sampling of U, k, epsilon: exact on fields linear in x, y, z (which
trilinear interpolation reproduces), NaN outside the box and in solids, linear in time."""
import numpy as np
import pytest
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

import lrigid

ORIGIN, H, N = np.array([-1.0, 0.0, 2.0]), 0.25, (9, 5, 7)


def linear(p, scale=1.0):
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    U = np.stack([1 + 0.5 * x - y, 2 * z, -0.25 * x + y + 0.1 * z], axis=-1) * scale
    return U, (0.3 + 0.1 * x + 0.05 * y + 0.02 * z) * scale, (0.2 + 0.01 * (x + y + z)) * scale


def write_vti(path, scale=1.0, solid=None, wall=None):
    img = vtkImageData()
    img.SetDimensions(*N)
    img.SetOrigin(*ORIGIN)
    img.SetSpacing(H, H, H)
    k, j, i = np.meshgrid(*(np.arange(n) for n in N[::-1]), indexing="ij")
    pts = ORIGIN + H * np.stack([i, j, k], axis=-1).reshape(-1, 3)  # x fastest
    U, kk, eps = linear(pts, scale)
    valid = np.ones(len(pts), np.uint8)
    if solid is not None:
        valid[solid(pts)] = 0
        U[valid == 0], kk[valid == 0], eps[valid == 0] = 0, 0, 0
    for name, a in (("U", U), ("k", kk), ("epsilon", eps)):
        arr = numpy_to_vtk(np.ascontiguousarray(a, np.float32), deep=True)
        arr.SetName(name)
        img.GetPointData().AddArray(arr)
    v = numpy_to_vtk(valid, deep=True)
    v.SetName("valid")
    img.GetPointData().AddArray(v)
    if wall is not None:
        a = numpy_to_vtk(np.ascontiguousarray(wall(pts), np.float32), deep=True)
        a.SetName("wall_distance")
        img.GetPointData().AddArray(a)
    w = vtkXMLImageDataWriter()
    w.SetFileName(str(path))
    w.SetInputData(img)
    assert w.Write() == 1
    return str(path)


def test_sampling_is_exact_on_a_linear_field(tmp_path):
    g = lrigid.Grid.load(write_vti(tmp_path / "lin.vti"))
    assert g.shape == N and g.spacing == (H, H, H) and g.origin == tuple(ORIGIN)
    rng = np.random.default_rng(4)
    upper = ORIGIN + H * (np.array(N) - 1)
    p = ORIGIN + rng.random((5000, 3)) * (upper - ORIGIN)
    p[0], p[1] = ORIGIN, upper  # the corners are inside
    s = g.sample(p)
    U, k, eps = linear(p)
    assert s["valid"].all()
    assert s["U"].shape == (5000, 3) and s["k"].shape == (5000,)
    assert np.allclose(s["U"], U, atol=1e-5)  # float32 grid values
    assert np.allclose(s["k"], k, atol=1e-6) and np.allclose(s["epsilon"], eps, atol=1e-6)
    out = g.sample([[-1.01, 0, 2], [0, 0, 100], [np.nan, 0, 3]])
    assert not out["valid"].any() and np.isnan(out["k"]).all() and np.isnan(out["U"]).all()


def test_wall_distance_is_the_plain_trilinear_blend(tmp_path):
    # a plane wall 0.3 x + 0.4 y - z + 2.6 = 0 (a signed distance up to the factor): linear,
    # so reproduced exactly, also where the points are solid (negative); +inf off the box and
    # on a grid without the array
    plane = lambda p: 0.3 * p[:, 0] + 0.4 * p[:, 1] - p[:, 2] + 2.6  # noqa: E731
    g = lrigid.Grid.load(write_vti(tmp_path / "w.vti", wall=plane,
                                   solid=lambda p: plane(p) < 0))
    p = np.array([[0.1, 0.5, 2.5], [0.6, 0.2, 3.1], [-0.5, 0.9, 2.2], [0.0, 0.0, 100.0]])
    w = g.sample(p)["wall_distance"]
    assert np.allclose(w[:3], plane(p[:3]), atol=1e-5)
    assert w[3] == np.inf
    bare = lrigid.Grid.load(write_vti(tmp_path / "bare.vti"))
    assert np.isinf(bare.sample(p[:1])["wall_distance"]).all()


def test_solid_points_and_time_series(tmp_path):
    solid = lambda p: p[:, 0] > 0.49  # noqa: E731  points with x >= 0.5 are solid
    f0 = write_vti(tmp_path / "a.vti", 1.0, solid)
    f1 = write_vti(tmp_path / "b.vti", 3.0, solid)
    with open(tmp_path / "s.pvd", "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                '<DataSet timestep="0" file="a.vti"/>\n<DataSet timestep="2" file="b.vti"/>\n'
                '</Collection>\n</VTKFile>\n')
    g = lrigid.Grid.load(tmp_path / "s.pvd")
    assert g.times == [0.0, 2.0]
    p = np.array([[0.1, 0.5, 2.5], [0.3, 0.5, 2.5], [0.45, 0.5, 2.5]])
    s = g.sample(p, t=0.5)  # a quarter of the way: scale 1.5
    # x = 0.1: all corners valid (0 and 0.25); x = 0.3 lies between 0.25 and 0.5 (solid), the
    # valid corner carries 80 % of the weight: it is in the fluid with that corner's values;
    # x = 0.45: 20 %, outside the fluid (the runtime's half-weight rule)
    assert list(s["valid"]) == [True, True, False]
    U, k, _ = linear(p, 1.5)
    assert np.allclose(s["U"][0], U[0], atol=1e-5) and s["k"][0] == pytest.approx(k[0], abs=1e-6)
    _, k_wall, _ = linear(np.array([[0.25, 0.5, 2.5]]), 1.5)
    assert s["k"][1] == pytest.approx(k_wall[0], abs=1e-6)
    assert np.allclose(g.sample(p[:1], t=99)["k"], linear(p[:1], 3.0)[1], atol=1e-6)  # clamped


def test_bad_grid_raises(tmp_path):
    with pytest.raises(lrigid.Error, match="nope.vti"):
        lrigid.Grid.load(tmp_path / "nope.vti")
    g = lrigid.Grid.load(write_vti(tmp_path / "lin.vti"))
    with pytest.raises(lrigid.Error, match=r"shape \(n, 3\)"):
        g.sample(np.zeros((4, 2)))
