"""Simulation state as NumPy arrays: reading, writing between steps, and pushes, against
analytic rigid-body results (Lamb's added mass of a sphere: rho_f V / 2, none in rotation)."""
import math

import numpy as np
import pytest

import lrigid

RHO_F, RHO_B, A = 1000.0, 2500.0, 0.01  # water, glass, radius 1 cm


def sphere_scene(effects, gravity=(0, 0, 0), n=3, duration=1.0):
    return lrigid.Scene.from_dict({
        "version": 1,
        "fluid": {"density": RHO_F, "kinematic_viscosity": 1e-6,
                  "uniform": {"U": [0, 0, 0], "k": 0, "epsilon": 0}},
        "gravity": list(gravity), "effects": effects,
        "integrator": {"scheme": "splitting", "dt": 0.001}, "duration": duration, "seed": 3,
        "bodies": [{"name": "glass", "shape": {"type": "sphere", "radius": A},
                    "density": RHO_B, "count": n, "spawn_box": [[0, 0, 0], [1, 1, 1]]}],
        "output": {"every": 0.1, "formats": ["csv"]}})


def test_shapes_and_initial_state():
    sim = lrigid.Simulation(sphere_scene(["added_mass"]))
    assert len(sim) == 3 and sim.t == 0 and sim.n_steps == 0
    assert sim.positions.shape == (3, 3) and sim.orientations.shape == (3, 4)
    assert sim.velocities.shape == (3, 3) and sim.angular_velocities.shape == (3, 3)
    assert sim.status.dtype == np.uint8 and list(sim.status) == [lrigid.MOVING] * 3
    assert sim.type_names == ["glass"] and list(sim.types) == [0, 0, 0]
    assert np.allclose(np.linalg.norm(sim.orientations, axis=1), 1, atol=1e-15)
    assert np.all((sim.positions >= 0) & (sim.positions <= 1))


def test_a_body_waits_unreleased_until_its_release_time():
    d = {"version": 1,
         "fluid": {"density": RHO_F, "kinematic_viscosity": 1e-6,
                   "uniform": {"U": [0, 0, 0], "k": 0, "epsilon": 0}},
         "gravity": [0, 0, -9.81], "effects": ["gravity"],
         "integrator": {"scheme": "splitting", "dt": 0.001}, "duration": 1.0, "seed": 3,
         "bodies": [{"name": "glass", "shape": {"type": "sphere", "radius": A},
                     "density": RHO_B, "count": 3, "spawn_box": [[0, 0, 0], [1, 1, 1]],
                     "release": {"times": [0, 0.25]}}]}  # bodies 0, 1 at 0; body 2 at 0.25 s
    sim = lrigid.Simulation(lrigid.Scene.from_dict(d))
    assert list(sim.status) == [lrigid.MOVING, lrigid.MOVING, lrigid.UNRELEASED]
    assert lrigid.STATUS_NAMES[lrigid.UNRELEASED] == "unreleased"
    start = sim.positions.copy()
    sim.step(200)  # 0.2 s
    assert sim.status[2] == lrigid.UNRELEASED
    assert np.array_equal(sim.positions[2], start[2]), "not stepped before its release"
    assert sim.positions[0][2] < start[0][2], "the others fall"
    sim.step(100)  # 0.3 s: body 2 falling for 0.05 s
    assert sim.status[2] == lrigid.MOVING
    assert sim.positions[2][2] < start[2][2], "falls from its release on"


def test_push_gives_the_analytic_velocities():
    sim = lrigid.Simulation(sphere_scene(["added_mass"]))
    V = 4 / 3 * math.pi * A ** 3
    m_eff = (RHO_B + RHO_F / 2) * V       # body plus Lamb's added mass
    inertia = 0.4 * RHO_B * V * A ** 2    # no rotational added mass for a sphere
    x = sim.positions[1].copy()           # a view follows the run: keep a copy
    J = np.array([0.01, -0.02, 0.005])    # N s
    r = np.array([0, 0, A])               # pushed at the top of the sphere
    sim.push(1, J, at=x + r)
    assert np.allclose(sim.velocities[1], J / m_eff, rtol=1e-12, atol=0)
    assert np.allclose(sim.angular_velocities[1], np.cross(r, J) / inertia, rtol=1e-12, atol=0)
    assert np.all(sim.velocities[[0, 2]] == 0)
    # it then flies straight (no drag, no gravity): x(t) = x0 + v t
    sim.step(250)
    assert sim.t == pytest.approx(0.25)
    assert np.allclose(sim.positions[1], x + J / m_eff * 0.25, rtol=0, atol=1e-12)
    sim.push(1, [0, 0, 0], angular_impulse=[0, 0, 1e-3])
    assert sim.angular_velocities[1][2] == pytest.approx(1e-3 / inertia
                                                         + np.cross(r, J)[2] / inertia)


def test_writing_the_state_between_steps():
    sim = lrigid.Simulation(sphere_scene(["gravity"], gravity=(0, 0, -9.81)))
    p = sim.positions.copy()              # a read-only view: change a copy
    p[:] = [[0, 0, 10], [1, 0, 10], [2, 0, 10]]
    sim.positions = p
    v = sim.velocities
    v[2] = [3.0, 0, 4.0]
    sim.velocities = v
    q = sim.orientations
    q[0] = [2, 0, 0, 2]                   # normalized on assignment
    sim.orientations = q
    assert np.array_equal(sim.positions, p)
    assert np.allclose(sim.orientations[0], [2 ** -0.5, 0, 0, 2 ** -0.5], atol=1e-15)
    w = sim.angular_velocities
    w[0] = [0, 0, 2.0]
    sim.angular_velocities = w
    assert np.allclose(sim.angular_velocities[0], [0, 0, 2.0], atol=1e-15)
    assert np.allclose(sim.velocities[2], [3, 0, 4], atol=1e-15)
    sim.run(until=0.5)
    # free fall, gravity only: z = z0 + v0 t - g t^2 / 2 (splitting: exact to round-off)
    t = 0.5
    assert sim.t == pytest.approx(t)
    z = sim.positions[:, 2]
    assert z[0] == pytest.approx(10 - 9.81 * t * t / 2, abs=1e-9)
    assert sim.positions[2][0] == pytest.approx(1 * 0 + 2 + 3 * t, abs=1e-9)
    assert z[2] == pytest.approx(10 + 4 * t - 9.81 * t * t / 2, abs=1e-9)
    assert sim.velocities[0][2] == pytest.approx(-9.81 * t, abs=1e-9)


def test_bad_state_input_raises():
    sim = lrigid.Simulation(sphere_scene(["added_mass"]))
    with pytest.raises(lrigid.Error, match=r"shape \(3, 3\)"):
        sim.positions = np.zeros((2, 3))
    with pytest.raises(lrigid.Error, match="finite"):
        sim.velocities = np.full((3, 3), np.nan)
    with pytest.raises(lrigid.Error, match="out of range"):
        sim.push(3, [1, 0, 0])
    with pytest.raises(lrigid.Error, match="seed"):
        lrigid.Simulation(sphere_scene(["added_mass"]), seed=-1)
    with pytest.raises(lrigid.Error, match="n must be >= 0"):
        sim.step(-1)


def test_views_follow_the_run_and_refuse_writes():
    sim = lrigid.Simulation(sphere_scene(["gravity"], gravity=(0, 0, -9.81)))
    x, status, types = sim.positions, sim.status, sim.types
    for view in (x, status, types):
        assert not view.flags.writeable and not view.flags.owndata and view.base is not None
    assert types.dtype == np.uint16 and status.dtype == np.uint8
    before = x.copy()
    sim.step(10)
    # the view taken before the steps holds the new positions: free fall, 10 steps of 1 ms
    assert np.array_equal(x, sim.positions)
    assert np.allclose(x[:, 2], before[:, 2] - 9.81 * 0.01 ** 2 / 2, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match="read-only"):
        x[0, 2] = 5.0
    with pytest.raises(ValueError, match="read-only"):
        status[0] = lrigid.LANDED
    # orientations are a copy (the run keeps x, y, z, w): writing one changes nothing
    q = sim.orientations
    q[0] = [0.0, 1.0, 0.0, 0.0]
    assert not np.array_equal(sim.orientations[0], q[0])
    # a view keeps its run alive
    last = x.copy()
    del sim
    assert np.array_equal(x, last)


def resting_scene(tmp_path):
    """two glass beads dropped 5 mm onto the ground in still water (they rest, then sleep after
    0.5 s of rest) and one released 50 m up (still falling)"""
    bead = {"name": "glass", "shape": {"type": "sphere", "radius": A}, "density": RHO_B}
    return lrigid.Scene.from_dict({
        "version": 1,
        "fluid": {"density": RHO_F, "kinematic_viscosity": 1e-6,
                  "uniform": {"U": [0, 0, 0], "k": 0, "epsilon": 0}},
        "gravity": [0, 0, -9.81], "effects": ["gravity", "buoyancy", "added_mass", "drag"],
        "integrator": {"scheme": "strang", "dt": 0.001}, "duration": 1.0, "seed": 3,
        "ground": {"z": 0.0},
        "bodies": [dict(bead, count=2, spawn_box=[[0, 0, A + 0.005], [1, 1, A + 0.005]]),
                   dict(bead, name="high", count=1, position=[0, 0, 50])],
        "output": {"every": 0.25, "formats": ["csv"]}}, name=str(tmp_path / "scene.json"))


def test_states_are_the_outputs_states(tmp_path):
    out = tmp_path / "out"
    sim = lrigid.Simulation(resting_scene(tmp_path), output_dir=out)
    status = sim.status
    assert list(sim.states) == ["flying"] * 3
    sim.run()
    states = sim.states
    assert states.dtype.kind == "U" and sim.state_codes.dtype == np.uint8
    assert list(states) == [lrigid.STATE_NAMES[c] for c in sim.state_codes]
    assert list(states) == ["sleeping", "sleeping", "flying"]
    assert list(status) == [lrigid.SLEEPING, lrigid.SLEEPING, lrigid.MOVING]
    # the names are the ones trajectories.csv writes for the last frame
    with open(out / "trajectories.csv") as f:
        last = [line.rstrip("\n").split(",")[-1] for line in f.readlines()[-3:]]
    assert last == list(states)
    assert {"flying", "sliding", "resting", "sleeping", "exited", "landed",
            "failed"} <= set(lrigid.STATE_NAMES)
