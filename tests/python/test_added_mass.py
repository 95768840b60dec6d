"""added_mass(shape, fluid_density): Lamb's exact tensors and the `lrigid added-mass` numbers."""
import json
import math
import os

import numpy as np
import pytest

import lrigid
from conftest import ROOT, cli


def test_sphere_is_half_the_displaced_mass():
    K = lrigid.added_mass({"type": "sphere", "radius": 0.1}, 1000.0)
    assert K.shape == (6, 6)
    m = 0.5 * 1000.0 * 4 / 3 * math.pi * 0.1 ** 3  # Lamb: rho V / 2, nothing in rotation
    assert np.allclose(K, np.diag([m, m, m, 0, 0, 0]), rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("shape, flags", [
    ({"type": "ellipsoid", "semi_axes": [0.03, 0.02, 0.001]}, ["--ellipsoid", "0.03", "0.02",
                                                              "0.001"]),
    ({"type": "box", "size": [0.06, 0.04, 0.0004], "panels": 300},
     ["--box", "0.06", "0.04", "0.0004", "--panels", "300"]),
    ({"type": "mesh", "file": os.path.join(ROOT, "tests", "data", "meshes", "cube_quads.obj")},
     ["--mesh", os.path.join(ROOT, "tests", "data", "meshes", "cube_quads.obj")]),
])
def test_same_tensor_as_the_command(lrigid_bin, shape, flags):
    if shape["type"] == "mesh" and not os.path.exists(shape["file"]):
        pytest.fail("test mesh missing: " + shape["file"])
    d = lrigid.added_mass(shape, 1.204, details=True)
    ref = json.loads(cli("added-mass", *flags, "--fluid-density", "1.204", "--json").stdout)
    assert d["method"] == ref["method"] and d["panels"] == ref["panels"]
    assert np.array_equal(d["added_mass"], np.array(ref["added_mass"]))
    assert d["volume"] == ref["volume"]
    assert np.array_equal(lrigid.added_mass(shape, 1.204), d["added_mass"])


def test_bad_shape_names_the_key():
    with pytest.raises(lrigid.Error, match=r"^<shape>: shape.radius: must be > 0, got -1"):
        lrigid.added_mass({"type": "sphere", "radius": -1}, 1000)
    with pytest.raises(lrigid.Error, match=r"shape.type: must be sphere, ellipsoid, box or mesh"):
        lrigid.added_mass({"type": "cone"}, 1000)
    with pytest.raises(lrigid.Error,
                       match=r'shape: unknown key "radios" \(did you mean "radius"\?\)'):
        lrigid.added_mass({"type": "sphere", "radius": 1, "radios": 2}, 1000)
    with pytest.raises(lrigid.Error, match="fluid_density"):
        lrigid.added_mass({"type": "sphere", "radius": 1}, -1)
