"""Ctrl-C during a long Simulation.run() or step(n): KeyboardInterrupt within a fraction of a
second, and the simulation left at a step boundary, usable afterwards."""
import os
import signal
import subprocess
import sys
import time

CHILD = r'''
import sys, time
import lrigid
sim = lrigid.Simulation(lrigid.Scene.from_dict({
    "version": 1,
    "fluid": {"density": 1.2, "kinematic_viscosity": 1.5e-5,
              "uniform": {"U": [1, 0, 0], "k": 0.1, "epsilon": 0.05}},
    "gravity": [0, 0, -9.81], "effects": "auto",
    "integrator": {"scheme": "splitting", "dt": 1e-4}, "duration": 1e5, "seed": 3,
    "bodies": [{"name": "bead", "shape": {"type": "sphere", "radius": 0.003},
                "density": 30, "count": 200, "position": [0, 0, 1e6]}],
    "output": {"every": 1, "formats": ["csv"]}}))
method = sys.argv[1]
print("ready", flush=True)
try:
    sim.run() if method == "run" else sim.step(10**9)
except KeyboardInterrupt:
    t = time.monotonic()
    n = sim.n_steps
    assert 0 < n < 10**9 and abs(sim.t - n * 1e-4) < 1e-9, (n, sim.t)
    sim.step(3)  # still usable: three more steps from where it stopped
    assert sim.n_steps == n + 3, (n, sim.n_steps)
    print("interrupted", time.monotonic(), flush=True)
    sys.exit(0)
print("finished", flush=True)
sys.exit(1)
'''


def interrupt(method):
    p = subprocess.Popen([sys.executable, "-c", CHILD, method], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=os.environ.copy())
    assert p.stdout.readline().strip() == "ready"
    time.sleep(1.0)  # well into the run
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        p.kill()
        raise AssertionError("Ctrl-C ignored: still running 20 s after SIGINT")
    assert p.returncode == 0, (out, err)
    words = out.split()
    assert words[0] == "interrupted", (out, err)
    return float(words[1]) - sent


def test_ctrl_c_stops_run_quickly():
    assert interrupt("run") < 0.5


def test_ctrl_c_stops_step_n_quickly():
    assert interrupt("step") < 0.5
