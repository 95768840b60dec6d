"""Running a scene with an lrigid built with plate_knobs.patch (README.md here): the LR_* factors
go in through the environment. Shared by coefficient_search.py, regimes.py and onset.py."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "lib"))
import vcommon as vc  # noqa: E402


def run_with_knobs(lrigid, scene, knobs, work, name):
    """Run `scene` (a dict) in work/name with the factors `knobs` ({"LR_CR": 0.5, ...}) and
    return its trajectories (vcommon.read_traj)."""
    env = dict(os.environ)
    env.update({k: repr(float(v)) for k, v in knobs.items()})
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    p = vc.write_scene(os.path.join(d, "scene.json"), scene)
    subprocess.run([lrigid, "run", p, "-o", os.path.join(d, "out"), "--quiet"], env=env,
                   check=True)
    return vc.read_traj(os.path.join(d, "out", "trajectories.csv"))
