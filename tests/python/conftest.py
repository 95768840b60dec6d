"""Shared fixtures of the Python module's tests (tests/python, ctest label `python`).

ctest runs them with PYTHONPATH=<build>/python and LRIGID_BUILD=<build>; by hand:
    PYTHONPATH=build/python LRIGID_BUILD=build /usr/bin/python3 -m pytest -q tests/python
"""
import copy
import json
import os
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("LRIGID_BUILD", os.path.join(ROOT, "build"))
LRIGID = os.path.join(BUILD, "bin", "lrigid")


@pytest.fixture(scope="session")
def lrigid_bin():
    assert os.access(LRIGID, os.X_OK), "%s not built (LRIGID_BUILD)" % LRIGID
    return LRIGID


def cli(*args, check=True):
    """Runs the lrigid command; returns the CompletedProcess (text)."""
    r = subprocess.run([LRIGID, *args], capture_output=True, text=True)
    if check:
        assert r.returncode == 0, r.stderr
    return r


def small_box_scene(cards=6, beads=6, duration=0.2, every=0.05):
    """scenes/uniform_box.json with fewer bodies and a short run: paper cards (box, the plates'
    batched step) and polystyrene beads (sphere, the spheres' batched step), turbulence on."""
    with open(os.path.join(ROOT, "scenes", "uniform_box.json")) as f:
        s = json.load(f)
    s = copy.deepcopy(s)
    s["bodies"][0]["count"] = cards
    s["bodies"][1]["count"] = beads
    s["duration"] = duration
    s["output"] = {"dir": "unused", "every": every, "formats": ["pvd"]}
    return s


def write_json(path, d):
    with open(path, "w") as f:
        json.dump(d, f, indent=1)
    return str(path)
