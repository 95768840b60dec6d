"""lrigid: rigid bodies in turbulent air and water, from Python (docs/python.md).

The same library the ``lrigid`` command runs on: scenes (``Scene``), runs whose state is read
and written as NumPy arrays (``Simulation``), the fluid Kirchhoff tensor of a shape
(``added_mass``), what ``lrigid explain`` reports (``explain``) and the flow grids written by
foam2grid (``Grid``). Units are SI everywhere. Bad input raises ``lrigid.Error`` (a
``ValueError``) with the command's message, naming the file (or dict), key and value.
"""
import json as _json
import os as _os

import numpy as _np

from . import _lrigid

__version__ = _lrigid.__version__
Error = _lrigid.Error
Error.__module__ = "lrigid"
Error.__doc__ = ("Bad input (scene, shape, grid, arguments): the message names the file or "
                 "dict, the key and the value, as the lrigid command's does.")

# status codes of Simulation.status (as in bodies.pvd's "status" array): MOVING stepped
# (flying, sliding or resting), LANDED stopped at a "stop" ground, EXITED left the grid or stopped
# at a "stop" wall, FAILED a non-finite state, SLEEPING resting on a surface where the flow cannot
# move it, not stepped until a gust wakes it (docs/contacts.md), UNRELEASED waiting for its
# release time (the scene's bodies[i].release), not stepped until then
MOVING, LANDED, EXITED, FAILED, SLEEPING, UNRELEASED = 0, 1, 2, 3, 4, 5
STATUS_NAMES = ("moving", "landed", "exited", "failed", "sleeping", "unreleased")

# the names of Simulation.state_codes in code order, as the outputs write a body's state
# (trajectories.csv's "state" column, bodies.pvd's "state" array): flying, sliding, resting,
# sleeping, exited, landed, failed, ... (from the library: a state it gains appears here)
STATE_NAMES = tuple(_lrigid.STATE_NAMES)
_STATE_NAMES_ARRAY = _np.array(STATE_NAMES)


def _dumps(d, what):
    try:
        return _json.dumps(d, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise Error("%s: cannot be written as JSON: %s" % (what, e)) from None


class Scene:
    """A validated scene (docs/scene-format.md, schema v1).

    Build it with ``Scene.load(path)`` or ``Scene.from_dict(d)``; read-only attributes:
    ``file``, ``seed``, ``dt`` (s), ``duration`` (s), ``integrator``, ``body_count``.
    """

    def __init__(self, compiled):
        self._s = compiled

    @staticmethod
    def load(path):
        """Reads a scene file; relative paths in it resolve against its folder."""
        return Scene(_lrigid.Scene.load(str(path)))

    @staticmethod
    def from_dict(d, name="<dict>"):
        """A scene from a dict with the file's schema. Relative paths in it resolve against the
        folder of ``name`` (default: the current directory); error messages name ``name``."""
        return Scene(_lrigid.Scene.from_json(_dumps(d, name), str(name)))

    def __getattr__(self, key):
        if key in ("file", "seed", "dt", "duration", "integrator", "body_count"):
            return getattr(self._s, key)
        raise AttributeError(key)

    def __repr__(self):
        return "lrigid.Scene(%r, %d bodies, dt=%g s, duration=%g s)" % (
            self.file, self.body_count, self.dt, self.duration)


class Simulation(_lrigid.Simulation):
    """A run of a scene, stepped exactly as ``lrigid run`` steps it.

    ``Simulation(scene, seed=None, threads=None, output_dir=None)``: ``seed`` overrides the
    scene's (as ``lrigid run --seed``), ``threads`` the thread count (default: all cores; results
    do not depend on it). Same seed: the same bits as ``lrigid run``
    (tests/python/test_same_bits.py).

    Recording: with ``output_dir`` the run writes the scene's outputs ("output.formats") into
    that folder as ``lrigid run -o output_dir`` does, frames at the scene's output times with
    pushes and edits included. The results are committed, all at once, when the run reaches the
    scene's duration (``run()`` with no argument); until then nothing appears under its final
    name. ``close()`` (or leaving a ``with`` block, or the object's end) before that abandons
    the recording: no result, the folder as it was. ``recording`` says whether a recording is
    under way, ``output_dir`` where it goes (None without one). The folder is refused as
    ``lrigid run`` refuses it (a result's name taken by a file lrigid did not write), and while
    another Simulation of this process records into it.

    Stepping: ``step(n=1)`` takes n steps of ``dt``; ``run(until=None)`` steps to the time
    ``until`` (s, rounded to a whole step; default the scene's duration). ``t`` (s) and
    ``n_steps`` say where the run is; stepping past the scene's duration is allowed.

    State (NumPy arrays, one row per body, in the order of trajectories.csv). Read-only views
    of the run's own arrays, no copy, that follow the run (take ``.copy()`` to keep a value):
    ``positions`` (N, 3) float centre of mass, m; ``status`` (N,) uint8 (MOVING, LANDED,
    EXITED, FAILED, SLEEPING, UNRELEASED); ``types`` (N,) uint16 index into ``type_names``.
    Copies, made at each read: ``orientations`` (N, 4) body -> world quaternion w, x, y, z; ``velocities``
    (N, 3) m/s and ``angular_velocities`` (N, 3) rad/s in world axes (as trajectories.csv);
    ``states`` (N,) str, each body's state as the outputs name it (``STATE_NAMES``: flying,
    sliding, resting, sleeping, exited, landed, failed, unreleased) and ``state_codes`` (N,)
    uint8 its index in ``STATE_NAMES``; ``stop_times`` (s) and ``reasons`` of stopped bodies.

    Changing the state between steps: assign a whole array, e.g.
    ``v = sim.velocities; v[3] += (0, 0, 1); sim.velocities = v`` or
    ``p = sim.positions.copy(); p[0, 2] = 1.0; sim.positions = p`` (orientations are
    normalized; world-frame velocities are stored in the body frame). ``push(body, impulse,
    angular_impulse=None, at=None)`` applies an impulse (N s, world frame) at the world point
    ``at`` (default the centre of mass) and an angular impulse (N m s): the body's generalized
    momentum, with its added mass, gains them; a landed body pushed moves again.
    """

    def __init__(self, scene, seed=None, threads=None, output_dir=None):
        if not isinstance(scene, Scene):
            raise Error("Simulation: scene must be an lrigid.Scene (Scene.load or "
                        "Scene.from_dict), got %s" % type(scene).__name__)
        if output_dir is not None:
            output_dir = _os.fspath(output_dir)
        super().__init__(scene._s, seed, threads, output_dir)

    @property
    def states(self):
        """(N,) str: each body's state as the outputs name it (``STATE_NAMES``), a copy."""
        return _STATE_NAMES_ARRAY[self.state_codes]

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def added_mass(shape, fluid_density, details=False):
    """The fluid Kirchhoff (added-mass) tensor of a shape, 6x6 NumPy array about the volume
    centroid, order (vx vy vz wx wy wz), units kg | kg m | kg m^2: the shape's own, as
    ``lrigid added-mass`` prints it but for a flat mesh whose surfaces are planes, for which the
    command prints its planform's tensor (the one a run takes) and this the panel solution of the
    mesh's own triangles.

    ``shape`` is a dict as a body's "shape" in a scene file, e.g. ``{"type": "sphere",
    "radius": 0.1}`` or ``{"type": "box", "size": [0.06, 0.04, 0.0004], "panels": 800}``;
    ``fluid_density`` in kg/m^3. With ``details=True`` returns a dict with also ``method``
    ("analytic" or "bem"), ``panels``, ``volume`` (m^3), ``centroid`` (m) and
    ``inertia_per_unit_density`` (m^5). Boundary-element results use the command's disk cache.
    """
    r = _lrigid.added_mass_json(_dumps(shape, "<shape>"), float(fluid_density), "<shape>")
    return r if details else r["added_mass"]


def explain(scene):
    """What ``lrigid explain`` prints, as a dict: fluid, flow scales, and per body type
    (``body_types``) the dimensionless numbers, each effect's size with keep/skip and reason,
    the effects simulated, the step taken and the estimated cost (ns per body-step).
    ``scene``: an ``lrigid.Scene``, a path or a dict."""
    if isinstance(scene, dict):
        scene = Scene.from_dict(scene)
    elif not isinstance(scene, Scene):
        scene = Scene.load(scene)
    return _lrigid.explain_scene(scene._s)


class Grid(_lrigid.Grid):
    """A grid written by foam2grid (.vti, or .pvd series), read whole (docs/grid-format.md).

    ``Grid.load(path)``; ``shape`` (points per axis), ``origin``, ``spacing`` (m), ``times``
    (s), ``kinematic_viscosity`` (m^2/s, 0 when the file has none).
    ``sample(points, t=0)`` with points an (n, 3) array (m) returns a dict of NumPy arrays
    ``U`` (n, 3) m/s, ``k`` (n,) m^2/s^2, ``epsilon`` (n,) m^2/s^3 and ``valid`` (n,) bool:
    trilinear in space over the valid corners of the cell (the runtime's rule: a point is in
    the fluid when valid corners carry at least half the weight; else NaN), linear in time
    between frames, clamped to the first and last frame.
    """

    @staticmethod
    def load(path):
        """Reads a grid file (.vti or .pvd)."""
        return Grid(str(path))


__all__ = ["Error", "Scene", "Simulation", "Grid", "added_mass", "explain", "MOVING", "LANDED",
           "EXITED", "FAILED", "SLEEPING", "STATUS_NAMES", "STATE_NAMES"]
