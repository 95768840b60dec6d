"""Simulation(scene, output_dir=D) records as `lrigid run -o D` does: the same files (bitwise,
summary.json but its timings), frames at the scene's output times with pushes in them, results
committed only when the run reaches the scene's duration, the same refusals of a folder."""
import csv
import json
import os
import re

import numpy as np
import pytest

import lrigid
from conftest import cli, small_box_scene, write_json

# what summary.json measures of the machine rather than of the run
TIMINGS = ("wall_seconds", "body_steps_per_second", "field_load_seconds")
RESULTS = ("trajectories.csv", "summary.json", "animation.glb", "bodies.pvd")


def recorded_scene(tmp_path, **changes):
    scene = small_box_scene(cards=4, beads=4, duration=0.2, every=0.05)
    scene["output"]["formats"] = ["csv", "pvd", "glb"]
    scene.update(changes)
    return write_json(tmp_path / "scene.json", scene)


def files_of(folder):
    """{relative path: bytes} of every file under folder"""
    out = {}
    for root, _, names in os.walk(folder):
        for n in names:
            p = os.path.join(root, n)
            with open(p, "rb") as f:
                out[os.path.relpath(p, folder)] = f.read()
    return out


def summary_without_timings(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    return {k: v for k, v in s.items() if k not in TIMINGS}


def rows(folder):
    with open(os.path.join(folder, "trajectories.csv")) as f:
        return list(csv.DictReader(f))


def test_recording_is_bitwise_the_command_output(lrigid_bin, tmp_path):
    path = recorded_scene(tmp_path)
    a, b = str(tmp_path / "a"), str(tmp_path / "b")
    cli("run", path, "-o", a, "--seed", "11", "--quiet")
    sim = lrigid.Simulation(lrigid.Scene.load(path), seed=11, output_dir=b)
    assert sim.recording and sim.output_dir == b
    sim.run()
    assert not sim.recording
    fa, fb = files_of(a), files_of(b)
    assert sorted(fa) == sorted(fb) and all(r in fa for r in RESULTS + ("landings.csv",))
    for name in fa:
        if name != "summary.json":
            assert fa[name] == fb[name], name
    sa, sb = summary_without_timings(a), summary_without_timings(b)
    assert sa == sb and sa["seed"] == 11 and sa["body_steps"] > 0
    # the comparison is not trivial: 5 frames (0, 0.05, ..., 0.2 s) of 8 moving bodies
    r = rows(b)
    assert len(r) == 5 * 8 and float(r[-1]["t"]) == pytest.approx(0.2)
    assert float(r[0]["z"]) != float(r[-8]["z"])


def test_recording_cut_into_steps_and_past_the_duration(lrigid_bin, tmp_path):
    path = recorded_scene(tmp_path)
    a, b = str(tmp_path / "a"), str(tmp_path / "b")
    cli("run", path, "-o", a, "--quiet")
    sim = lrigid.Simulation(lrigid.Scene.load(path), output_dir=b, threads=1)
    for n in (7, 1, 30, 13):          # steps of 2 ms; outputs every 25 steps
        sim.step(n)
    assert sim.recording and not any(os.path.exists(os.path.join(b, r)) for r in RESULTS)
    sim.step(200)                      # through the duration (100 steps) and beyond
    assert not sim.recording and sim.n_steps == 251
    assert files_of(a)["trajectories.csv"] == files_of(b)["trajectories.csv"]
    assert files_of(a)["animation.glb"] == files_of(b)["animation.glb"]


def sphere_scene(tmp_path):
    """two glass beads at rest in still water without gravity: only a push moves them"""
    return lrigid.Scene.from_dict({
        "version": 1,
        "fluid": {"density": 1000.0, "kinematic_viscosity": 1e-6,
                  "uniform": {"U": [0, 0, 0], "k": 0, "epsilon": 0}},
        "gravity": [0, 0, 0], "effects": ["added_mass"],
        "integrator": {"scheme": "splitting", "dt": 0.001}, "duration": 0.5, "seed": 3,
        "bodies": [{"name": "glass", "shape": {"type": "sphere", "radius": 0.01},
                    "density": 2500.0, "count": 2, "position": [0, 0, 1]}],
        "output": {"every": 0.1, "formats": ["csv"]}}, name=str(tmp_path / "scene.json"))


def test_frames_show_a_push(tmp_path):
    out = str(tmp_path / "out")
    sim = lrigid.Simulation(sphere_scene(tmp_path), output_dir=out)
    sim.run(until=0.2)
    m_eff = (2500.0 + 1000.0 / 2) * 4 / 3 * np.pi * 0.01 ** 3  # Lamb's added mass
    sim.push(1, [0.0, 0.0, 0.003])
    sim.run()
    r = rows(out)
    assert [float(x["t"]) for x in r[::2]] == pytest.approx([0, 0.1, 0.2, 0.3, 0.4, 0.5])
    v = 0.003 / m_eff
    for row in r:
        t, body = float(row["t"]), int(row["body"])
        moved = body == 1 and t > 0.2 + 1e-9
        # trajectories.csv prints 9 significant digits
        assert float(row["vz"]) == pytest.approx(v if moved else 0.0, rel=1e-8, abs=1e-15)
        assert float(row["z"]) == pytest.approx(1 + (v * (t - 0.2) if moved else 0), rel=1e-8)


def test_unfinished_recording_leaves_the_folder_as_it_was(tmp_path):
    out = str(tmp_path / "out")
    lrigid.Simulation(sphere_scene(tmp_path), output_dir=out).run()
    before = files_of(out)
    assert "trajectories.csv" in before
    with lrigid.Simulation(sphere_scene(tmp_path), output_dir=out) as sim:
        sim.push(0, [0.0, 0.001, 0.0])
        sim.run(until=0.3)
        assert sim.recording
    assert files_of(out) == before    # no temporaries left, the earlier results unchanged
    # a second recording into a folder lrigid wrote replaces its results
    sim = lrigid.Simulation(sphere_scene(tmp_path), output_dir=out)
    sim.push(0, [0.0, 0.001, 0.0])
    sim.run()
    assert files_of(out)["trajectories.csv"] != before["trajectories.csv"]


def test_folder_refused_as_the_command_refuses_it(lrigid_bin, tmp_path):
    path = recorded_scene(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    (out / "trajectories.csv").write_text("mine\n")
    r = cli("run", path, "-o", str(out), "--quiet", check=False)
    assert r.returncode == 4
    message = r.stderr.splitlines()[0].split("error: ", 1)[1]
    assert "trajectories.csv" in message
    with pytest.raises(lrigid.Error) as e:
        lrigid.Simulation(lrigid.Scene.load(path), output_dir=out)
    assert str(e.value) == message
    assert (out / "trajectories.csv").read_text() == "mine\n"
    assert sorted(os.listdir(out)) == ["trajectories.csv"]


def test_one_recording_at_a_time_into_a_folder(tmp_path):
    out = str(tmp_path / "out")
    first = lrigid.Simulation(sphere_scene(tmp_path), output_dir=out)
    with pytest.raises(lrigid.Error, match="another run of this process is recording"):
        lrigid.Simulation(sphere_scene(tmp_path), output_dir=str(tmp_path / "." / "out"))
    first.close()
    assert not first.recording
    second = lrigid.Simulation(sphere_scene(tmp_path), output_dir=out)
    second.run()
    assert os.path.exists(os.path.join(out, "summary.json"))


def test_bad_output_dir_is_a_clear_error(tmp_path):
    a_file = tmp_path / "notes.txt"
    a_file.write_text("not a folder\n")
    for bad in (a_file, a_file / "out"):
        with pytest.raises(lrigid.Error, match=re.escape("%s: cannot create directory" % bad)):
            lrigid.Simulation(sphere_scene(tmp_path), output_dir=bad)
    assert a_file.read_text() == "not a folder\n"
    with pytest.raises(lrigid.Error, match="output_dir: an empty name"):
        lrigid.Simulation(sphere_scene(tmp_path), output_dir="")
