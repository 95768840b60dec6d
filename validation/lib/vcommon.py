"""Shared helpers for the validation studies (run binaries, write scenes, record verdicts).

Every study script calls `Study(name, description)`, records checks with `check()` (a measured
value against a stated reference, tolerance and source) and ends with `finish()`, which prints
PASS/FAIL lines and writes <work>/<study>/results.json for validation/run_all.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend)
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# The scheme of the shipped scenes (scenes/*.json; runtime/src/model/scene.h kDefaultIntegrator):
# the studies validate the model as it ships, so they run it unless they are about a scheme
SCHEME = "strang"


def parse_args(extra=None):
    p = argparse.ArgumentParser()
    p.add_argument("--build", default=os.path.join(ROOT, "build"), help="build dir with bin/")
    p.add_argument("--work", default=None, help="work dir (default <build>/validation)")
    p.add_argument("--quick", action="store_true", help="reduced sample sizes")
    if extra:
        extra(p)
    a = p.parse_args()
    a.build = os.path.abspath(a.build)
    if a.work is None:
        a.work = os.path.join(a.build, "validation")
    a.work = os.path.abspath(a.work)
    a.lrigid = os.path.join(a.build, "bin", "lrigid")
    a.foam2grid = os.path.join(a.build, "bin", "foam2grid")
    return a


def import_lrigid(args):
    """The Python module lrigid of the build (docs/python.md): <build>/python on sys.path."""
    sys.path.insert(0, os.path.join(args.build, "python"))
    try:
        import lrigid
    except ImportError as e:
        sys.exit("cannot import lrigid from %s/python (%s): build the module (docs/python.md)"
                 % (args.build, e))
    return lrigid


class Study:
    def __init__(self, key, title, args):
        self.key, self.title, self.args = key, title, args
        self.dir = os.path.join(args.work, key)
        os.makedirs(self.dir, exist_ok=True)
        self.rows, self.plots, self.notes, self.tables = [], [], [], []
        self.t0 = time.time()

    def path(self, *p):
        return os.path.join(self.dir, *p)

    def check(self, name, measured, reference, tol, source, unit="", rel=False, note="",
              verdict=None, tol_text=None):
        """Record |measured − reference| ≤ tol (absolute, or relative to |reference| if rel).

        verdict may be given explicitly for checks that are not a single number (then measured
        and reference are printed as text)."""
        if verdict is None:
            try:
                m, r = float(measured), float(reference)
                err = abs(m - r) / abs(r) if rel else abs(m - r)
                ok = bool(np.isfinite(m) and err <= tol)
            except (TypeError, ValueError):
                ok = False
            verdict = "PASS" if ok else "FAIL"
        if tol_text is None:
            tol_text = ("±%.3g %%" % (100 * tol)) if rel else ("±%s" % fmt(tol))
        row = dict(study=self.key, check=name, measured=fmt(measured), reference=fmt(reference),
                   unit=unit, tolerance=tol_text, source=source, verdict=verdict, note=note)
        self.rows.append(row)
        print("%s  %s: measured %s %s, reference %s %s (tol %s) [%s]" % (
            verdict, name, row["measured"], unit, row["reference"], unit, tol_text, source),
            flush=True)
        return verdict == "PASS"

    def fail(self, name, why, source=""):
        self.check(name, "not run", "-", 0, source, verdict="FAIL", tol_text="-", note=why)

    def savefig(self, fig, name, caption):
        p = self.path(name)
        fig.savefig(p + ".tmp.png", dpi=90, bbox_inches="tight")
        os.replace(p + ".tmp.png", p)
        plt.close(fig)
        self.plots.append(dict(file=name, caption=caption))

    def note(self, text):
        self.notes.append(text)

    def table(self, lines):
        """a Markdown block (list of lines) for the report, after the notes"""
        self.tables.append(list(lines))

    def finish(self):
        out = dict(study=self.key, title=self.title, rows=self.rows, plots=self.plots,
                   notes=self.notes, tables=self.tables, seconds=time.time() - self.t0,
                   quick=self.args.quick)
        tmp = self.path("results.json.tmp")
        with open(tmp, "w") as f:
            json.dump(out, f, indent=1)
        os.replace(tmp, self.path("results.json"))
        nfail = sum(r["verdict"] != "PASS" for r in self.rows)
        print("%s: %d checks, %d failed, %.1f s" % (self.key, len(self.rows), nfail,
                                                   out["seconds"]))
        sys.exit(1 if nfail or not self.rows else 0)


def fmt(x):
    if isinstance(x, str):
        return x
    try:
        x = float(x)
    except (TypeError, ValueError):
        return str(x)
    if x == 0:
        return "0"
    if abs(x) >= 1e4 or abs(x) < 1e-3:
        return "%.4g" % x
    return "%.4g" % x


def run(cmd, log=None, env=None, cwd=None, check=True):
    """Run a command; on failure print its output tail and raise."""
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                       cwd=cwd)
    if log:
        with open(log, "w") as f:
            f.write(r.stdout)
    if check and r.returncode != 0:
        raise RuntimeError("command failed (%d): %s\n%s" % (r.returncode, " ".join(cmd),
                                                            r.stdout[-3000:]))
    return r


def write_scene(path, scene):
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def run_scene(args, scene, name, threads=1):
    """Write scene to <dir>/<name>.json, run lrigid, return (trajectories, summary)."""
    d = os.path.dirname(name)
    os.makedirs(d, exist_ok=True)
    sp = write_scene(name + ".json", scene)
    out = name + "_out"
    run([args.lrigid, "run", sp, "-o", out, "--quiet", "--threads", str(threads)])
    with open(os.path.join(out, "summary.json")) as f:
        summ = json.load(f)
    traj = None
    if os.path.exists(os.path.join(out, "trajectories.csv")):
        traj = read_traj(os.path.join(out, "trajectories.csv"))
    return traj, summ, out


def read_traj(path):
    """trajectories.csv -> dict of arrays shaped (frames, bodies) per column (v, w world frame)."""
    cols = ["body", "type", "t", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz",
            "wx", "wy", "wz"]
    num = [c for c in cols if c != "type"]
    a = np.loadtxt(path, delimiter=",", skiprows=1, usecols=[i for i, c in enumerate(cols)
                                                            if c != "type"], ndmin=2)
    body = a[:, 0].astype(int)
    nb = body.max() + 1
    nf = len(body) // nb
    out = {}
    for j, c in enumerate(num):
        out[c] = a[:, j].reshape(nf, nb)
    return out

def wind_scene_json(quick):
    """scenes/leaves_wind.json on ./Allrun's grid (or LRIGID_WIND_GRID, another conversion of
    the same case), its counts scaled to 1000 bodies (200 with quick, which also runs 10 s),
    outputs every 0.5 s in csv; (None, why) when the grid is missing."""
    grid = os.environ.get("LRIGID_WIND_GRID") or os.path.join(ROOT, "results", "grids",
                                                              "windCourtyard.vti")
    if not os.path.exists(grid):
        return None, ("no %s (run ./Allrun's precompute first, or set LRIGID_WIND_GRID)" % grid)
    s = json.load(open(os.path.join(ROOT, "scenes", "leaves_wind.json")))
    s["fluid"]["field"] = grid
    n = 200 if quick else 1000
    total = sum(b["count"] for b in s["bodies"])
    for b in s["bodies"]:
        b["count"] = max(1, round(b["count"] * n / total))
    if quick:
        s["duration"] = 10.0
    s["output"] = {"every": 0.5, "formats": ["csv"]}
    return s, ""


def uniform_fluid(rho, nu, U=(0, 0, 0), k=0.0, eps=0.0):
    return dict(density=rho, kinematic_viscosity=nu, uniform=dict(U=list(U), k=k, epsilon=eps))


WATER = dict(rho=998.2, mu=1.0016e-3)
AIR = dict(rho=1.204, mu=1.813e-5)


def foam_env():
    """Environment for Debian's OpenFOAM v1912 (never its etc/bashrc) and the project's cases."""
    env = dict(os.environ)
    env.update(WM_PROJECT_DIR="/usr/share/openfoam", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               FOAM_CASES_DIR=os.path.join(ROOT, "foam_cases"))
    return env


def case_stamp(name):
    """hash of the committed-style sources of foam_cases/<name> (0.orig, constant, system, ...)."""
    import hashlib
    src = os.path.join(ROOT, "foam_cases", name)
    h = hashlib.sha1()
    for dp, dn, fn in os.walk(src):
        rel = os.path.relpath(dp, src)
        top = rel.split(os.sep)[0]
        if rel != "." and top not in ("0.orig", "constant", "system"):
            dn[:] = []
            continue
        if rel == "constant":
            dn[:] = [d for d in dn if d != "polyMesh"]  # generated by Allrun
        dn.sort()
        for f in sorted(fn):
            if rel == "." and f not in ("Allrun", "Allclean"):
                continue
            p = os.path.join(dp, f)
            h.update(p[len(src):].encode())
            with open(p, "rb") as fh:
                h.update(fh.read())
    return h.hexdigest()


def foam_case(args, name):
    """Run foam_cases/<name>/Allrun in <work>/cases/<name> once; later calls (other studies of
    the same run_all) reuse it while the case's sources are unchanged. Returns the case dir."""
    import shutil
    src = os.path.join(ROOT, "foam_cases", name)
    stamp = case_stamp(name)
    dst = os.path.join(args.work, "cases", name)
    marker = os.path.join(dst, ".validation_done")
    if os.path.exists(marker) and open(marker).read().strip() == stamp:
        return dst
    shutil.rmtree(dst, ignore_errors=True)
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    os.makedirs(dst)
    for f in ("Allrun", "Allclean"):
        shutil.copy2(os.path.join(src, f), dst)
    for d in ("0.orig", "constant", "system"):
        shutil.copytree(os.path.join(src, d), os.path.join(dst, d),
                        ignore=shutil.ignore_patterns("polyMesh"))
    run([os.path.join(dst, "Allrun")], log=os.path.join(dst, "log.Allrun"), env=foam_env())
    with open(marker, "w") as f:
        f.write(stamp + "\n")
    return dst


def latest_time(case):
    import re
    ts = [d for d in os.listdir(case) if re.fullmatch(r"[0-9.eE+-]+", d) and d != "0"]
    return max(ts, key=float)
