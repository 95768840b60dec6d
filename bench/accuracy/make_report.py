#!/usr/bin/python3
"""Turns the accuracy study's CSV (bench/accuracy/accuracy_study) into
  OUT/error_vs_cost.png   error versus cost, log-log, one curve per integrator, Pareto front marked
  OUT/grid_error.png      grid error against the finest grid, per metric (when grid rows exist)
  OUT/slopes.csv          measured convergence slopes
  OUT/tolerance_table.json  what `lrigid run --tolerance E` chooses from
  OUT/accuracy.csv        all points (the inputs merged)
  DOC (docs/accuracy.md)  method, machine, date, headline findings written from the numbers
usage: make_report.py --csv A.csv [B.csv ...] --out DIR [--doc FILE] [--study-seconds S]
"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SRC = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCHEMES = ["euler", "rk4", "splitting", "strang"]
COLORS = {"euler": "tab:red", "rk4": "tab:blue", "splitting": "tab:green",
          "splitting_float": "tab:olive", "strang": "tab:purple"}


def atomic_write(path, write):
    tmp = path + ".tmp"
    with open(tmp, "w" if not path.endswith(".png") else "wb") as f:
        write(f)
    os.replace(tmp, path)


def read_rows(paths):
    """the rows of the CSVs; a point measured in several (scene, sweep, scheme, dt, substeps,
    effects, grid, metric) is kept from the run with the most bodies, the finer Monte Carlo
    estimate (bench/accuracy/run_fine_mc.sh reruns a stochastic sweep with more bodies)"""
    rows, where = [], {}
    for p in paths:
        if not os.path.exists(p):
            continue
        with open(p) as f:
            for r in csv.DictReader(f):
                for k in ("dt", "error", "error_se", "ref_check", "ns_per_body_step",
                          "cpu_ns_per_body_step", "wall_s", "wall_total_s", "cpu_s"):
                    r[k] = float(r.get(k) or 0)
                for k in ("substeps", "bodies", "valid", "body_steps", "failed"):
                    r[k] = int(r[k])
                key = tuple(r[k] for k in ("scene", "sweep", "integrator", "dt", "substeps",
                                           "effects", "grid", "metric"))
                if key in where:
                    if r["bodies"] > rows[where[key]]["bodies"]:
                        rows[where[key]] = r
                    continue
                where[key] = len(rows)
                rows.append(r)
    if not rows:
        sys.exit("make_report.py: no rows in " + ", ".join(paths))
    return rows


DET_NS = {}      # (scene, integrator, dt) -> CPU ns per body-step with turbulence off
TURB_FACTOR = {}  # scene -> CPU cost with turbulence / without (effects sweep, substeps 1)


def index_costs(rows):
    for r in rows:
        if r["sweep"] == "dt_det":
            DET_NS[(r["scene"], r["integrator"], r["dt"])] = r["cpu_ns_per_body_step"]
    for scene in {r["scene"] for r in rows}:
        on = [r for r in rows if r["scene"] == scene and r["sweep"] == "effects"
              and r["effects"] == "auto"]
        off = [r for r in rows if r["scene"] == scene and r["sweep"] == "effects_det"
               and r["effects"] == "auto"]
        if on and off and off[0]["cpu_ns_per_body_step"] > 0:
            TURB_FACTOR[scene] = on[0]["cpu_ns_per_body_step"] / off[0]["cpu_ns_per_body_step"]


def cost(r):
    """CPU seconds per body per simulated second (process CPU time, robust on a shared
    machine; the wall time is in the CSV too). A stochastic sweep run sums r = dt/h fine
    increments per step to keep the Brownian path, which production runs (substeps 1) do not:
    its cost is the turbulence-off run's at the same scheme and dt times the scene's measured
    turbulence factor (auto effects, substeps 1)."""
    ns = r["cpu_ns_per_body_step"] or r["ns_per_body_step"]
    key = (r["scene"], r["integrator"], r["dt"])
    if r["sweep"] in ("dt_stoch", "reference_stoch") and key in DET_NS:
        ns = DET_NS[key] * TURB_FACTOR.get(r["scene"], 1.0)
    return ns * 1e-9 / r["dt"]


def usable(r):
    """a point whose error is above what the reference and Monte Carlo can resolve"""
    if not r["valid"] or r["failed"] or not math.isfinite(r["error"]) or r["error"] <= 0:
        return False
    if r["error"] < 3 * r["ref_check"]:
        return False
    if r["error_se"] > 0 and r["error"] < 2 * r["error_se"]:
        return False
    return True


def fit(points):
    n = len(points)
    if n < 3:
        return float("nan")
    xs = [math.log(d) for d, _ in points]
    ys = [math.log(e) for _, e in points]
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")


def scene_kind(scene):
    """same rule as runtime/src/model/tolerance.cpp scene_kind()"""
    path = os.path.join(SRC, "scenes", scene + ".json")
    if not os.path.exists(path):
        return None
    s = json.load(open(path))
    fluid = s.get("fluid", {})
    field = "grid" if "field" in fluid else "uniform"
    medium = "air" if fluid.get("density", 1000) < 100 else "water"
    return field + "-" + medium


def pareto(points):
    """points (cost, error, label): the ones no other point beats in both"""
    front = []
    for p in sorted(points):
        if not front or p[1] < front[-1][1]:
            front.append(p)
    return front


def sweep_points(rows, scene, sweep, metric):
    out = {}
    for r in rows:
        if r["scene"] == scene and r["sweep"] == sweep and r["metric"] == metric:
            out.setdefault(r["integrator"], []).append(r)
    for k in out:
        out[k].sort(key=lambda r: r["dt"])
    return out


def table_points(rows, scene):
    """per (integrator, dt): the relative error used by --tolerance, the largest of the
    deterministic trajectory error at the first compared time and the weak errors of the mean
    and variance of positions (each plus 2 Monte Carlo standard errors: no point claims more
    than 1000 bodies resolve); cost from the turbulence-off run times the turbulence factor"""
    det = {(r["integrator"], r["dt"]): r for r in rows
           if r["scene"] == scene and r["sweep"] == "dt_det" and r["metric"] == "trajectory_t1"}
    weak = {}
    for r in rows:
        if r["scene"] == scene and r["sweep"] == "dt_stoch" and r["metric"] in TOL_WEAK:
            weak.setdefault((r["integrator"], r["dt"]), []).append(r)
    # schemes without a stochastic sweep (run_study.sh leaves rk4 out by default) are not offered
    stoch = {k[0] for k in weak}
    pts = []
    for key in sorted(set(det) | set(weak)):
        if key[0] not in stoch:
            continue
        parts = ([det[key]] if key in det else []) + weak.get(key, [])
        if any(not x["valid"] or x["failed"] for x in parts):
            continue
        err = max(x["error"] + 2 * x["error_se"] for x in parts)
        sto = weak.get(key)
        c = cost(sto[0]) if sto else cost(det[key]) * TURB_FACTOR.get(scene, 1.0)
        pts.append({"integrator": key[0], "dt": key[1], "error": err, "cost": c})
    return pts


TOL_WEAK = ("weak_mean", "weak_var")


def plot(rows, scenes, path):
    panels = [("dt_det", "trajectory", "deterministic: trajectory error (max over times)"),
              ("dt_det", "trajectory_t1", "deterministic: trajectory error, first time"),
              ("dt_stoch", "strong", "stochastic: strong error (same Brownian path)"),
              ("dt_stoch", "weak_mean", "stochastic: weak error of the mean position")]
    fig, axes = plt.subplots(len(scenes), len(panels), figsize=(5 * len(panels), 4 * len(scenes)),
                             squeeze=False)
    for i, scene in enumerate(scenes):
        for j, (sweep, metric, title) in enumerate(panels):
            ax = axes[i][j]
            allp = []
            for integ, rs in sweep_points(rows, scene, sweep, metric).items():
                rs = [r for r in rs if r["valid"] and not r["failed"] and r["error"] > 0]
                if not rs:
                    continue
                xs = [cost(r) for r in rs]
                ys = [r["error"] for r in rs]
                ax.loglog(xs, ys, "o-", color=COLORS.get(integ), label=integ)
                if metric.startswith("weak"):
                    ax.errorbar(xs, ys, yerr=[2 * r["error_se"] for r in rs], fmt="none",
                                color=COLORS.get(integ), alpha=0.5)
                for r, x, y in zip(rs, xs, ys):
                    ax.annotate("%g" % r["dt"], (x, y), fontsize=6, alpha=0.7)
                    allp.append((x, y, integ))
            front = pareto(allp)
            if front:
                ax.loglog([p[0] for p in front], [p[1] for p in front], "k--", lw=1,
                          label="Pareto front")
                ax.scatter([p[0] for p in front], [p[1] for p in front], s=80,
                           facecolors="none", edgecolors="k")
            ref = [r["ref_check"] for r in rows if r["scene"] == scene and r["sweep"] == sweep
                   and r["metric"] == metric]
            if ref and max(ref) > 0:
                ax.axhline(max(ref), color="gray", ls=":", lw=1, label="reference check")
            ax.axhline(0.01, color="gray", ls="-", lw=0.5)
            ax.set_title("%s\n%s" % (scene, title), fontsize=9)
            ax.set_xlabel("cost: CPU s per body per simulated s")
            ax.set_ylabel("relative error")
            finish_axes(ax)
    save_figure(fig, path)


def finish_axes(ax):
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)


def save_figure(fig, path):
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)


def grid_points(n):
    """the points per axis of a grid file name grid_<case>_<N>.vti (0 if it has none)"""
    digits = n.rsplit("_", 1)[-1].split(".")[0]
    return int(digits) if digits.isdigit() else 0


GRID_METRICS = ["trajectory", "trajectory_t1", "weak_mean", "weak_var", "landing_mean",
                "landing_var"]


def plot_grid(rows, path):
    """grid error against the finest grid, per metric, against the points per axis"""
    fig, ax = plt.subplots(figsize=(6, 4.5))
    scenes = sorted({r["scene"] for r in rows if r["sweep"] == "grid"})
    for metric in GRID_METRICS:
        rs = sorted((r for r in rows if r["sweep"] == "grid" and r["metric"] == metric
                     and r["valid"] and r["error"] > 0), key=lambda r: grid_points(r["grid"]))
        if not rs:
            continue
        xs = [grid_points(r["grid"]) for r in rs]
        ys = [r["error"] for r in rs]
        ax.errorbar(xs, ys, yerr=[2 * r["error_se"] for r in rs], fmt="o-", capsize=3,
                    label=metric)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("grid points per axis (N^3 grid)")
    ax.set_ylabel("relative error against the finest grid")
    ax.set_title("grid error (%s; error bars: 2 Monte Carlo s.e.)" % ", ".join(scenes),
                 fontsize=9)
    finish_axes(ax)
    save_figure(fig, path)


def machine():
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        model = [l.split(":", 1)[1].strip() for l in out.splitlines() if l.startswith("Model name")]
        cpus = [l.split(":", 1)[1].strip() for l in out.splitlines() if l.startswith("CPU(s)")]
        return "%s, %s CPUs (lscpu), %s" % (model[0] if model else "?", cpus[0] if cpus else "?",
                                           platform.platform())
    except OSError:
        return platform.platform()


def fmt(x):
    return "%.3g" % x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", nargs="+", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--doc")
    ap.add_argument("--study-seconds", type=float, default=float("nan"))
    ap.add_argument("--note", default="", help="a line for the document (e.g. the commit)")
    a = ap.parse_args()
    rows = read_rows(a.csv)
    index_costs(rows)
    os.makedirs(a.out, exist_ok=True)

    # merged CSV
    fields = list(csv.DictReader(open([p for p in a.csv if os.path.exists(p)][0])).fieldnames)

    def write_csv(f):
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)

    merged = os.path.join(a.out, "accuracy.csv")
    if os.path.abspath(merged) not in [os.path.abspath(p) for p in a.csv]:
        atomic_write(merged, write_csv)

    dt_scenes = sorted({r["scene"] for r in rows if r["sweep"] in ("dt_det", "dt_stoch")})
    # slopes
    slopes = []
    for scene in dt_scenes:
        for sweep, metrics in (("dt_det", ["trajectory", "trajectory_t1"]),
                               ("dt_stoch", ["strong", "weak_mean", "weak_var", "landing_mean",
                                             "landing_var"])):
            for metric in metrics:
                for integ, rs in sorted(sweep_points(rows, scene, sweep, metric).items()):
                    pts = [(r["dt"], r["error"]) for r in rs if usable(r)]
                    slopes.append({"scene": scene, "sweep": sweep, "metric": metric,
                                   "integrator": integ, "slope": fit(pts), "points": len(pts),
                                   "dt_min": min((p[0] for p in pts), default=float("nan")),
                                   "dt_max": max((p[0] for p in pts), default=float("nan"))})

    def write_slopes(f):
        w = csv.DictWriter(f, fieldnames=list(slopes[0].keys()))
        w.writeheader()
        for s in slopes:
            w.writerow(s)

    if slopes:
        atomic_write(os.path.join(a.out, "slopes.csv"), write_slopes)

    # tolerance table
    kinds = {}
    sources = {}
    for scene in dt_scenes:
        k = scene_kind(scene)
        if k is None:
            continue
        pts = table_points(rows, scene)
        if k in kinds:  # two scenes of one kind: keep the larger error per (integrator, dt)
            old = {(p["integrator"], p["dt"]): p for p in kinds[k]}
            for p in pts:
                q = old.get((p["integrator"], p["dt"]))
                if q is None or p["error"] > q["error"]:
                    old[(p["integrator"], p["dt"])] = p
            pts = sorted(old.values(), key=lambda p: (p["integrator"], p["dt"]))
        kinds[k] = pts
        sources.setdefault(k, []).append(scene)
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    table = {"generated": date, "machine": machine(), "scenes": sources,
             "error": "relative error: the largest of the deterministic (turbulence off) "
                      "trajectory error RMS |x - x_ref| / RMS displacement at the first compared "
                      "time and the weak errors of the mean and variance of positions at the "
                      "last time, each plus 2 Monte Carlo standard errors",
             "cost": "CPU seconds per body per simulated second, one thread",
             "kinds": kinds}
    atomic_write(os.path.join(a.out, "tolerance_table.json"),
                 lambda f: json.dump(table, f, indent=1))

    if dt_scenes:
        plot(rows, dt_scenes, os.path.join(a.out, "error_vs_cost.png"))
    if any(r["sweep"] == "grid" for r in rows):
        plot_grid(rows, os.path.join(a.out, "grid_error.png"))
    if a.doc:
        text = report(rows, slopes, kinds, sources, dt_scenes, date, a.study_seconds, a.note)
        atomic_write(a.doc, lambda f: f.write(text))
    print("make_report.py: wrote %s (%d points, %d slopes)" % (a.out, len(rows), len(slopes)))


def precision_section(rows, w):
    """what the batched steps' single precision costs: splitting in float against double at the
    same dt (accuracy_study's "precision" sweep), beside the time-step error of both"""
    prec = [r for r in rows if r["sweep"] == "precision" and r["metric"] == "trajectory"]
    if not prec:
        return
    det = {(r["scene"], r["integrator"], r["dt"]): r for r in rows
           if r["sweep"] == "dt_det" and r["metric"] == "trajectory"}
    w("## What single precision costs")
    w("")
    w("`\"integrator\": {\"precision\": \"float\"}` runs the batched steps (spheres, plates, "
      "ellipsoids on a steady field) in single precision. Turbulence off, the same bodies as "
      "above: the trajectory error of splitting in double and in float against the reference, "
      "the float run's distance from the double run at the same dt (relative, as the "
      "trajectory error), and the CPU cost of each. Where float and double agree exactly the "
      "scene's bodies take the scalar step (a time-dependent field: the tank), which is always "
      "double.")
    w("")
    w("| scene | dt (s) | error, double | error, float | float vs double | CPU ns per "
      "body-step, double | float |")
    w("|---|---|---|---|---|---|---|")
    for r in sorted(prec, key=lambda r: (r["scene"], r["dt"])):
        d = det.get((r["scene"], "splitting", r["dt"]))
        f = det.get((r["scene"], "splitting_float", r["dt"]))
        e = lambda x: ("%.3g" % x["error"]) if x and x["valid"] else "–"  # noqa: E731
        c = lambda x: ("%.0f" % x["cpu_ns_per_body_step"]) if x else "–"  # noqa: E731
        w("| %s | %g | %s | %s | %s | %s | %s |" %
          (r["scene"], r["dt"], e(d), e(f), e(r), c(d), c(f)))
    w("")


def cheapest(pts, tol):
    ok = [p for p in pts if p["error"] <= tol]
    return min(ok, key=lambda p: p["cost"]) if ok else None


def report(rows, slopes, kinds, sources, scenes, date, seconds, note=""):
    L = []
    w = L.append
    w("# Accuracy versus cost")
    w("")
    w("Generated by `bench/accuracy/run_study.sh` (tool `bench/accuracy/accuracy_study.cpp`, "
      "report `bench/accuracy/make_report.py`) on %s. Machine: %s." % (date, machine()))
    if math.isfinite(seconds):
        w("The study took %.0f s (wall, shared machine)." % seconds)
    if note:
        w(note)
    w("Do not edit by hand: rerun the study. All numbers: `docs/accuracy/accuracy.csv`; slopes: "
      "`docs/accuracy/slopes.csv`; plot: `docs/accuracy/error_vs_cost.png`; the table "
      "`lrigid run --tolerance` reads: `docs/accuracy/tolerance_table.json`.")
    w("")
    w("![error versus cost](accuracy/error_vs_cost.png)")
    w("")
    w("## Headline findings (from the measured numbers)")
    w("")
    for kind, pts in sorted(kinds.items()):
        for tol in (0.1, 0.01, 0.001):
            c = cheapest(pts, tol)
            if c:
                w("* `%s` scenes (%s): the cheapest way to %g %% relative error is **%s at dt = "
                  "%g s** (measured %.2g, %.3g CPU s per body per simulated s)." %
                  (kind, ", ".join(sources[kind]), tol * 100, c["integrator"], c["dt"],
                   c["error"], c["cost"]))
            else:
                best = min(pts, key=lambda p: p["error"]) if pts else None
                w("* `%s` scenes: no measured point reaches %g %% (smallest: %s at dt = %g s, "
                  "%.2g)." % (kind, tol * 100, best["integrator"] if best else "-",
                              best["dt"] if best else 0, best["error"] if best else 0))
    for scene in scenes:
        # what the stochastic sweep can resolve: a weak error is claimed with 2 Monte Carlo
        # standard errors added, so no point can show less than its own 2 SE
        floor = {m: min((2 * r["error_se"] for r in rows if r["scene"] == scene and
                         r["sweep"] == "dt_stoch" and r["metric"] == m and r["valid"] and
                         not r["failed"]), default=float("nan")) for m in TOL_WEAK}
        ref = [r for r in rows if r["scene"] == scene and r["sweep"] == "reference_stoch"]
        if ref and all(math.isfinite(v) for v in floor.values()):
            w("* `%s`: the weak errors' Monte Carlo floor (2 standard errors of the paired "
              "differences, the smallest over the swept points) is %.2g for the mean and %.2g for "
              "the variance: no point can show a smaller `--tolerance` error, except the "
              "stochastic reference's own step (%s at dt = %g s), whose weak errors are 0 by "
              "construction." % (scene, floor["weak_mean"], floor["weak_var"],
                                 ref[0]["integrator"], ref[0]["dt"]))
    det = {(s["scene"], s["integrator"]): s for s in slopes
           if s["sweep"] == "dt_det" and s["metric"] == "trajectory"}
    for scene in scenes:
        first = {(r["integrator"], r["dt"]): r["error"] for r in rows if r["scene"] == scene
                 and r["sweep"] == "dt_det" and r["metric"] == "trajectory_t1" and r["valid"]}
        whole = {(r["integrator"], r["dt"]): r["error"] for r in rows if r["scene"] == scene
                 and r["sweep"] == "dt_det" and r["metric"] == "trajectory" and r["valid"]}
        dts = sorted(d for (i, d) in whole if i == "euler" and (i, d) in first)
        rk = sorted(d for (i, d) in whole if i == "rk4")
        if dts and rk:
            d, dr = dts[0], rk[0]
            w("* `%s`, turbulence off: euler at dt = %g s has trajectory error %.2g at the first "
              "compared time and %.2g at the worst; rk4 at dt = %g s %.2g and %.2g. An error "
              "that grows over time much faster than the step's (flat bodies tumbling: a small "
              "difference changes how they flip) makes long-horizon pathwise errors saturate, "
              "so `--tolerance` uses the first compared time and the weak errors." %
              (scene, d, first[("euler", d)], whole[("euler", d)], dr,
               first.get(("rk4", dr), float("nan")), whole[("rk4", dr)]))
    for scene in scenes:
        r = det.get((scene, "rk4"))
        if r and math.isfinite(r["slope"]) and r["slope"] < 3:
            w("* On `%s` rk4 converges with slope %.2f, not 4: the drag of flat bodies has "
              "kinks (through |direction cosines|), first order, and tumbling amplifies them, "
              "so rk4's extra stages buy accuracy only through a smaller error constant. (The "
              "study's bodies stop where they first touch the ground, ground.contact \"stop\", "
              "a touchdown located inside the step: not the cause.)" %
              (scene, r["slope"]))
    eff = [r for r in rows if r["sweep"] in ("effects_det", "effects") and
           r["effects"] != "full" and r["valid"]]
    for r in eff:
        if r["metric"] in ("trajectory", "weak_mean"):
            full = [x for x in rows if x["scene"] == r["scene"] and x["sweep"] == r["sweep"]
                    and x["effects"] == "full" and x["metric"] == r["metric"]]
            speed = (cost(full[0]) / cost(r)) if full and cost(r) > 0 else float("nan")
            w("* `%s`, effect set `%s` against `full` (%s, %s): %s error %.2g%s, cost ratio "
              "full/%s = %.2f." %
              (r["scene"], r["effects"], r["integrator"], "dt %g s" % r["dt"], r["metric"],
               r["error"], (" ± %.1g" % r["error_se"]) if r["error_se"] else "", r["effects"],
               speed))
    for scene in scenes:
        land = [r for r in rows if r["scene"] == scene and r["sweep"] == "dt_stoch"
                and r["metric"].startswith("landing") and r["valid"]]
        if not land:
            continue
        for integ in SCHEMES:
            mine = sorted((r for r in land if r["integrator"] == integ), key=lambda r: r["dt"])
            for metric in ("landing_mean", "landing_var"):
                pts = [r for r in mine if r["metric"] == metric]
                if not pts:
                    continue
                what = "mean" if metric == "landing_mean" else "variance"
                w("* `%s` landing points, weak error of the %s, %s (%s): %s." %
                  (scene, what, integ, pts[0]["note"] or "landed bodies",
                   ", ".join("dt %g s: %.2g ± %.1g" % (r["dt"], r["error"], r["error_se"])
                             for r in pts)))
    for scene in scenes:
        bad = sorted({(r["integrator"], r["dt"]) for r in rows if r["scene"] == scene
                      and r["sweep"] in ("dt_det", "dt_stoch") and r["failed"]})
        if bad:
            w("* `%s`: bodies failed (non-finite state) with %s; those points are not used." %
              (scene, ", ".join("%s at dt %g s" % b for b in bad)))
    grid = [r for r in rows if r["sweep"] == "grid" and r["valid"]]
    for metric in GRID_METRICS:
        rs = sorted((r for r in grid if r["metric"] == metric),
                    key=lambda r: grid_points(r["grid"]))
        if rs:
            w("* grid error of the `%s` (%s, %s at dt %g s) against the finest grid: %s." %
              (metric, rs[0]["scene"], rs[0]["integrator"], rs[0]["dt"],
               ", ".join("%d³ %.2g%s" % (grid_points(r["grid"]), r["error"],
                                         (" ± %.1g" % r["error_se"]) if r["error_se"] else "")
                         for r in rs)))
    w("")
    w("## Measured convergence slopes")
    w("")
    w("Least-squares slope of log(error) against log(dt) over the points above 3× the "
      "reference check and 2 Monte Carlo standard errors. Theory "
      "(docs/physics/integrators.md): deterministic euler 1, rk4 4, splitting 1, strang 2; "
      "stochastic (additive noise) strong 1 and weak 1 (rk4 adds the noise once per step; strang measured "
      "weak 2 on a smooth case, tests/accuracy/strang_test.cpp).")
    w("The clean orders on smooth cases are asserted by `tests/accuracy/convergence_test.cpp` "
      "and `tests/accuracy/strang_test.cpp` (label `accuracy`).")
    w("")
    w("| scene | sweep | metric | integrator | slope | points | dt range (s) |")
    w("|---|---|---|---|---|---|---|")
    for s in slopes:
        w("| %s | %s | %s | %s | %s | %d | %s |" %
          (s["scene"], s["sweep"], s["metric"], s["integrator"],
           fmt(s["slope"]) if math.isfinite(s["slope"]) else "–", s["points"],
           ("%g–%g" % (s["dt_min"], s["dt_max"])) if s["points"] else "–"))
    w("")
    w("## Error and cost per integrator and dt")
    w("")
    w("Error: the `--tolerance` error, the largest of the deterministic trajectory error at the "
      "first compared time and the weak errors of the mean and variance of positions (each plus "
      "2 Monte Carlo standard errors); cost: CPU s per body per simulated s (one thread).")
    w("")
    for kind, pts in sorted(kinds.items()):
        w("### `%s` (%s)" % (kind, ", ".join(sources[kind])))
        w("")
        w("| integrator | dt (s) | relative error | cost |")
        w("|---|---|---|---|")
        for p in sorted(pts, key=lambda p: (p["integrator"], p["dt"])):
            w("| %s | %g | %.3g | %.3g |" % (p["integrator"], p["dt"], p["error"], p["cost"]))
        w("")
    precision_section(rows, w)
    grid = [r for r in rows if r["sweep"] == "grid"]
    if grid:
        w("## Grid error")
        w("")
        w("![grid error](accuracy/grid_error.png)")
        w("")
        w("The same scene and Brownian path on coarser conversions of one OpenFOAM case, against "
          "the finest; cost: CPU ns per body-step.")
        w("")
        w("| grid | turbulence | metric | relative error | Monte Carlo s.e. | bodies | CPU ns per "
          "body-step | note |")
        w("|---|---|---|---|---|---|---|---|")
        for r in sorted(grid, key=lambda r: (GRID_METRICS.index(r["metric"])
                                             if r["metric"] in GRID_METRICS else 9,
                                             grid_points(r["grid"]))):
            w("| %s | %s | %s | %s | %s | %d | %.0f | %s |" %
              (r["grid"], "off" if r["metric"].startswith("trajectory") else "on", r["metric"],
               "%.3g" % r["error"] if r["valid"] else "–",
               "%.2g" % r["error_se"] if r["error_se"] else "–", r["bodies"],
               r["cpu_ns_per_body_step"], r["note"]))
        w("")
    w("## Reference checks")
    w("")
    for r in rows:
        if r["sweep"].startswith("reference"):
            w("* %s, %s %s: %s at dt = %g s against the reference at dt/2: %.2g" %
              (r["scene"], r["sweep"], r["metric"], r["integrator"], r["dt"], r["error"]))
    w("")
    w(METHOD)
    return "\n".join(L) + "\n"


METHOD = """## Method

**Scenes.** The standard scenes of `scenes/` whose fields exist: `uniform_box` (uniform field,
always), `leaves_wind` (the steady windCourtyard case, after `./Allrun`) and `debris_tank` (the
transient tankJet series, frames 0.5 s apart interpolated in time, after `./Allrun -all`);
skipped otherwise, with a message. `uniform_box` and `debris_tank` run for 2 s, compared at
t = 0.5, 1, 1.5, 2 s. In `leaves_wind` the leaves are spawned 0.5-3 m above the ground instead
of the scene's 14-20 m (which take ~15 s to fall) and run for 4 s, compared at t = 1, 2, 3, 4 s,
so that about 90 % of its 1200 stochastic bodies land and the landing points can be compared.
Body counts are scaled: 100 bodies for the deterministic sweeps, 1000 (wind: 1200) for the
stochastic ones. Each scene runs in its own process, one thread, side by side.

**Deterministic error** (turbulence removed from every body type): positions against rk4 at
dt = h = 1e-4 s; that reference is checked against rk4 at 2h. Trajectory error = max over the
compared times of RMS_bodies |x − x_ref| / RMS_bodies |x_ref(t) − x_ref(0)| (relative to how far
the bodies moved).

**Stochastic error.** The noise is a Brownian path resolved at h: a run at dt = r·h uses
`noise_substeps = r`, so it sums the reference's increments and every dt sees the same path. The
reference is the splitting scheme at h, checked against the splitting at 2h. `run_study.sh`
sweeps euler, splitting and strang here (rk4's sweep would cost as much again;
`ACCURACY_STOCH_INTEGRATORS=euler,rk4,splitting,strang` adds it), and `--tolerance` offers only the
schemes that have a stochastic sweep. Strong error: the
same pathwise formula. Weak errors: the mean position |⟨x⟩ − ⟨x_ref⟩| / L and the total variance
|V − V_ref| / V_ref at the last time, and the same for the horizontal landing points of bodies that
landed in both runs (needs ≥ 30; the CSV's note gives how many). Monte Carlo error bars come
from the paired differences (common random numbers), so they measure how well the *difference*
is known.

**Effect sets.** `full` (every effect the build knows), `auto` (the scene's automatic selection)
and `minimal` (gravity, buoyancy, drag, mean flow, turbulence) at the scene's integrator and dt,
against `full`: with turbulence off (trajectory error: `trajectory` the worst over the compared
times, `trajectory_t1` at the first) and on (weak errors).

**Grid error.** One OpenFOAM case converted with `foam2grid --resolution N N N` at N = 32, 64,
128 and 256 (the solved coarse windCourtyard case, copied, with `./Allrun`'s bounds), the wind
scene as in the main study (leaves spawned 0.5-3 m high, 4 s, 100 / 1200 bodies, the same seed
and Brownian path) at its integrator and dt, against the 256³ grid: with turbulence off
(trajectory error) and on (weak errors of positions and landing points). Without the wind case,
`run_study.sh` runs the tiny OpenFOAM case instead (16³-128³).

**Cost.** Process CPU time of the integration per body-step (and wall time, in the CSV) measured
in the same run, one thread. The machine is shared by other jobs, so wall times scatter (the
load is given above); CPU times are steadier. Cost per simulated second = CPU time per
body-step / dt. The stochastic sweep's own runs are *not* used for cost: to keep one Brownian
path they sum dt/h fine increments per step (`noise_substeps`), a cost per step that grows
with dt/h and that production runs (substeps 1) never pay. Their cost is the turbulence-off
run's at the same scheme and dt times the scene's turbulence factor, measured in the effect-set sweep
(auto effects with and without turbulence, substeps 1).

**Scene kinds** (for `lrigid run --tolerance E`): `<field>-<medium>`, field `uniform` or `grid`
(a CFD field adds shear and k gradients), medium `air` when the fluid density is below
100 kg/m³ (bodies 10²–10³ times denser than the fluid, thin ones with stiff drag) else `water`
(density ratios of order 1: added mass and buoyancy dominate). `--tolerance E` picks, among the
measured points of the scene's kind (else a kind with the same medium), the cheapest whose error
is ≤ E, overrides `integrator.scheme` and `integrator.dt`, and prints its choice. Its error
is the largest of the deterministic trajectory error at the first compared time (0.5 s; wind
1 s) and the weak errors of the mean and variance of positions at the last time, each plus 2
Monte Carlo standard errors. Not the strong error nor the trajectory error over the whole run:
flat bodies tumble, so a small difference in one step changes when they flip and pathwise
differences grow to the size of the spread within a second or two at any dt (compare the
metrics `trajectory_t1` and `trajectory` in the CSV); the statistics of many bodies are what a
scene's result depends on.

**CSV columns** (`accuracy.csv`): scene, sweep (`reference_det`, `dt_det`, `reference_stoch`,
`dt_stoch`, `effects_det`, `effects`, `grid`), integrator, dt (s), substeps, effects, grid,
bodies, metric, error (relative), error_se (Monte Carlo standard error), valid, ref_check (the
reference's own error for that metric), body_steps, wall_s, ns_per_body_step (wall),
wall_total_s, cpu_s, cpu_ns_per_body_step, failed, note.

Regenerate: `cmake --build build --target accuracy_study foam2grid && bench/accuracy/run_study.sh build`.
A reduced version runs in the tests: `ctest -L accuracy`.
"""

if __name__ == "__main__":
    main()
