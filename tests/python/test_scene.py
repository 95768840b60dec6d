"""Scene.load / Scene.from_dict: the scene file's schema and the command's error messages."""
import json
import os

import pytest

import lrigid
from conftest import ROOT, cli, small_box_scene, write_json


def test_load_and_from_dict_agree():
    path = os.path.join(ROOT, "scenes", "uniform_box.json")
    a = lrigid.Scene.load(path)
    with open(path) as f:
        b = lrigid.Scene.from_dict(json.load(f))
    assert a.file == path and b.file == "<dict>"
    for key in ("seed", "dt", "duration", "integrator", "body_count"):
        assert getattr(a, key) == getattr(b, key)
    assert (a.seed, a.dt, a.duration, a.body_count) == (7, 0.002, 4.0, 400)


def test_error_is_a_value_error():
    assert issubclass(lrigid.Error, ValueError)


def test_missing_file_same_message_as_cli(lrigid_bin, tmp_path):
    path = str(tmp_path / "nope.json")
    with pytest.raises(lrigid.Error) as e:
        lrigid.Scene.load(path)
    r = cli("run", path, check=False)
    assert r.returncode == 3
    assert str(e.value) in r.stderr
    assert "file not found" in str(e.value) and path in str(e.value)


@pytest.mark.parametrize("edit, key", [
    (lambda s: s["bodies"][1]["shape"].update(radius=-1), "bodies[1].shape.radius"),
    (lambda s: s["fluid"].update(densty=1.2),
     'fluid: unknown key "densty" (did you mean "density"?)'),
    (lambda s: s["integrator"].update(scheme="leapfrog"), "integrator.scheme"),
])
def test_bad_scene_same_message_as_cli(lrigid_bin, tmp_path, edit, key):
    s = small_box_scene()
    edit(s)
    path = write_json(tmp_path / "bad.json", s)
    with pytest.raises(lrigid.Error) as from_file:
        lrigid.Scene.load(path)
    with pytest.raises(lrigid.Error) as from_dict:
        lrigid.Scene.from_dict(s, name=path)
    r = cli("run", path, check=False)
    assert r.returncode == 3
    assert str(from_file.value) == str(from_dict.value)
    assert str(from_file.value) in r.stderr
    assert key in str(from_file.value)
    # the default name says the scene came from a dict
    with pytest.raises(lrigid.Error) as named:
        lrigid.Scene.from_dict(s)
    assert str(named.value).startswith("<dict>: " + key)


def test_from_dict_rejects_what_json_cannot_hold():
    s = small_box_scene()
    s["duration"] = float("nan")
    with pytest.raises(lrigid.Error, match="cannot be written as JSON"):
        lrigid.Scene.from_dict(s)


def test_simulation_needs_a_scene():
    with pytest.raises(lrigid.Error, match="lrigid.Scene"):
        lrigid.Simulation({"version": 1})
