#!/usr/bin/python3
"""The batched step (runtime/src/integrate/rigid_batch.h: spheres, plates, ellipsoids, meshes)
against the scalar step, and what single precision costs in accuracy. Writes
docs/batched-step.md (machine and date stamped).

    bench/perf/batch_bench.py [--build build] [--out build/perf/batch] [--quick]
                              [--wind-case DIR] [--no-peers]

Scene: scenes/beads_wind.json (500 um glass beads in the courtyard wind, the parcels of
bench/peers/run_peers.sh), which needs results/grids/windCourtyard.vti (./Allrun).
Throughput: `lrigid bench` (splitting, the scene's effects) for the scalar step (integrator
batched = false), the batched step in double and in float, N = 10^4 and 10^5, 1 and 2 threads.
Peer, in the same run: OpenFOAM's icoUncoupledKinematicParcelFoam on the same parcels
(bench/peers/run_peers.sh --skip-mujoco: the same 500 um glass beads, N = 10^4, dt = 2 ms,
200 steps, sphereDrag, dispersion off and on), per core (CPU time) against lrigid's per-core rate;
the solved wind case from --wind-case or build/perf/peers_1000/windCourtyard (run_perf.sh's),
else solved once (about 2 min). And MuJoCo 2.2's ellipsoid fluid model stepping the same beads
(bench/peers/mujoco_harness --body bead: free spheres, contacts off, one body per model, RK4 and
Euler), per CPU second.
Accuracy: `lrigid run` of the scene for 10 s; landing points of float against double, next to
the time-step error (dt against dt/2) of the same scene without turbulence (deterministic, so the
difference is the discretization alone), and with turbulence (where any perturbation grows).
The same for the full leaves model: scenes/leaves_wind.json (leaves, paper sheets and seed pods,
the scene's own effects) with 0.5 s of warm-up before the timed steps (the start, bodies at rest
in the wind, hands more steps to the scalar step), against the same OpenFOAM parcels and MuJoCo
stepping the scene's seed pods (mujoco_harness's default body), and its float cost on landing
points without turbulence (art.turbulence_scale = 0). And the full effect set (every effect on
every type, Basset history and Magnus included) on the leaves scene: N = 10^4 on one thread and
300,000 bodies on two, double and float.
About 10 minutes on 2 cores.
"""
import argparse
import csv
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

ALL_EFFECTS = "all"  # lrigid bench --effects all: every effect of the registry on every body type
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def scene_variant(base, out_dir, name, batched=True, precision="double", dt=None,
                  turbulence=True, output=None, bodies=None):
    s = json.load(open(base))
    if bodies:
        s["bodies"] = [b for b in s["bodies"] if b["name"] in bodies]
    if not turbulence and not isinstance(s["effects"], list):
        # "auto" effects: keep the choice, turn the fluctuation off
        s.setdefault("art", {})["turbulence_scale"] = 0.0
        turbulence = True
    s["fluid"]["field"] = os.path.join(ROOT, "results/grids/windCourtyard.vti")
    s["integrator"]["batched"] = batched
    s["integrator"]["precision"] = precision
    if dt:
        s["integrator"]["dt"] = dt
    if not turbulence:
        s["effects"] = [e for e in s["effects"] if e != "turbulence"]
    s["output"] = {"dir": output or os.path.join(out_dir, name), "every": 1.0,
                   "formats": ["csv"]}
    path = os.path.join(out_dir, name + ".json")
    json.dump(s, open(path, "w"), indent=1)
    return path


def bench(lrigid, scene, n, threads, json_out, quick, warmup=2, effects="auto"):
    """The faster of two runs (this VM has slow episodes of a minute or so)."""
    steps = "5e5" if quick else "2e6"
    best = None
    for _ in range(1 if quick else 2):
        subprocess.run([lrigid, "bench", scene, "--n", str(n), "--threads", str(threads),
                        "--integrators", "splitting", "--effects", effects, "--body-steps",
                        steps, "--min-steps", "20", "--warmup", str(warmup), "--quiet", "--json",
                        json_out], check=True)
        run = json.load(open(json_out))["runs"][0]
        if best is None or run["body_steps_per_s"] > best["body_steps_per_s"]:
            best = run
    return (best["body_steps_per_s"], best["body_steps_per_cpu_s"], best["state_bytes_per_body"],
            best.get("scalar_handoffs", 0) / max(best["body_steps"], 1),
            best.get("newton_steps", 0) / max(best["body_steps"], 1))


def mujoco_peer(harness, body, label, quick):
    """MuJoCo's one-body-per-model rates (bench/peers/mujoco_harness, N = 10^4, dt = 2 ms), the
    faster of two runs for each integrator"""
    best = None
    for rep in range(1 if quick else 2):
        print("batch_bench.py: MuJoCo peer (%s), run %d" % (label, rep + 1), file=sys.stderr)
        got = json.loads(subprocess.run(
            [harness] + body + ["--n", "10000", "--steps", "200", "--dt", "0.002",
                                "--one-model-max", "100"],
            check=True, capture_output=True, text=True).stdout)
        if best is None:
            best = got
        else:
            for key in ("rk4", "euler"):
                best["one_body_per_model"][key] = max(best["one_body_per_model"][key],
                                                      got["one_body_per_model"][key])
    return best


def landings(lrigid, scene, out):
    subprocess.run([lrigid, "run", scene, "--quiet"], check=True, stdout=subprocess.DEVNULL)
    pts = {}
    with open(os.path.join(out, "landings.csv")) as f:
        for row in csv.DictReader(f):
            pts[int(row["body"])] = np.array([float(row["x"]), float(row["y"])])
    return pts


def landing_diff(a, b):
    common = sorted(set(a) & set(b))
    d = np.array([np.linalg.norm(a[i] - b[i]) for i in common])
    return {"landed_a": len(a), "landed_b": len(b), "common": len(common),
            "median": float(np.median(d)) if len(d) else float("nan"),
            "p90": float(np.percentile(d, 90)) if len(d) else float("nan"),
            "max": float(d.max()) if len(d) else float("nan")}


def machine():
    cpu = "?"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    return {"cpu": cpu, "cores": os.cpu_count(), "python": platform.python_version(),
            "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            "commit": subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                                     capture_output=True, text=True).stdout.strip(),
            "load": " ".join(open("/proc/loadavg").read().split()[:3])}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build/perf/batch"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "docs/batched-step.md"))
    ap.add_argument("--quick", action="store_true", help="shorter runs (a check of the script)")
    ap.add_argument("--wind-case", help="a solved windCourtyard case for the OpenFOAM peer")
    ap.add_argument("--no-peers", action="store_true", help="skip the OpenFOAM peer")
    args = ap.parse_args()
    lrigid = os.path.join(args.build, "bin/lrigid")
    base = os.path.join(ROOT, "scenes/beads_wind.json")
    if not os.path.exists(os.path.join(ROOT, "results/grids/windCourtyard.vti")):
        sys.exit("batch_bench.py: results/grids/windCourtyard.vti missing (./Allrun)")
    os.makedirs(args.out, exist_ok=True)
    m = machine()

    variants = [("scalar step, double", dict(batched=False)),
                ("batched, double", dict(batched=True)),
                ("batched, float", dict(batched=True, precision="float"))]
    ns = [10000, 100000]

    def throughput(scene_file, tag, warmup):
        rows = []
        for label, kw in variants:
            name = f"tp_{tag}_" + label.replace(", ", "_").replace(" ", "_")
            scene = scene_variant(scene_file, args.out, name, **kw)
            for n in ns:
                for t in (1, 2):
                    print(f"batch_bench.py: {tag}, {label}, N = {n}, {t} thread(s)",
                          file=sys.stderr)
                    rate, cpu_rate, bpb, handoff, _ = bench(
                        lrigid, scene, n, t, os.path.join(args.out, f"{name}_{n}_{t}.json"),
                        args.quick, warmup)
                    rows.append({"variant": label, "n": n, "threads": t, "rate": rate,
                                 "cpu_rate": cpu_rate, "bytes_per_body": bpb,
                                 "scalar_handoff_fraction": handoff})
        return rows

    rows = throughput(base, "beads", 2)
    leaves = os.path.join(ROOT, "scenes/leaves_wind.json")
    leaf_rows = throughput(leaves, "leaves", 250)
    # the full effect set: every effect on every type (Basset history and Magnus too, and
    # added mass and buoyancy for the seed pods, which the scene's "auto" leaves out): N = 10^4
    # on one thread and 300,000 bodies on two, double and float
    leaf_all = {"effects": ALL_EFFECTS, "runs": []}
    for key, names, prec, n, t in (
            ("all", None, "double", 10000, 1), ("all", None, "float", 10000, 1),
            ("plates", ("leaf", "paper"), "double", 10000, 1),
            ("pods", ("seed_pod",), "double", 10000, 1),
            ("all", None, "double", 300000, 2), ("all", None, "float", 300000, 2)):
        print(f"batch_bench.py: leaves, every effect, bodies: {key}, {prec}, N = {n}, "
              f"{t} thread(s)", file=sys.stderr)
        # (not the scene's own name: bench's JSON would overwrite the scene)
        name = f"tp_leaves_all9_{key}_{prec}"
        scene = scene_variant(leaves, args.out, name, bodies=names, precision=prec)
        out = os.path.join(args.out, f"{name}_{n}_{t}.json")
        rate, cpu_rate, bpb, handoff, newton = bench(lrigid, scene, n, t, out, args.quick, 250,
                                                     ALL_EFFECTS)
        leaf_all["runs"].append({"bodies": key, "precision": prec, "n": n, "threads": t,
                                 "rate": rate, "cpu_rate": cpu_rate, "bytes_per_body": bpb,
                                 "scalar_handoff_fraction": handoff,
                                 "newton_fraction": newton})

    peers = None
    if not args.no_peers:
        wind = args.wind_case or os.path.join(ROOT, "build/perf/peers_1000/windCourtyard")
        cmd = [os.path.join(ROOT, "bench/peers/run_peers.sh"), os.path.join(args.out, "peers"),
               "--n", "10000", "--steps", "200", "--dt", "0.002", "--build", args.build,
               "--skip-mujoco"]
        if os.path.isdir(wind):
            cmd += ["--wind-case", wind]
        # the faster of two runs at each setting, as for lrigid
        for rep in range(1 if args.quick else 2):
            print("batch_bench.py: OpenFOAM peer (run_peers.sh --skip-mujoco), run %d" % (rep + 1),
                  file=sys.stderr)
            with open(os.path.join(args.out, "peers.log"), "a") as log:
                subprocess.run(cmd, check=True, stdout=log, stderr=subprocess.STDOUT)
            got = json.load(open(os.path.join(args.out, "peers", "peers.json")))
            if peers is None:
                peers = got
            else:
                for key in ("dispersion_off", "dispersion_on"):
                    peers["openfoam"][key] = max(peers["openfoam"][key], got["openfoam"][key])
                peers["load"] += " / " + got.get("load", "?")

    def accuracy(scene_file, prefix, turbs):
        acc = {}
        for turb in turbs:
            tag = "turb" if turb else "det"
            runs = {}
            for key, kw in (("double", {}), ("float", dict(precision="float")),
                            ("double_half_dt", dict(dt=0.001))):
                if turb and key == "double_half_dt":
                    continue  # the noise differs with dt: no discretization error to compare
                name = f"acc_{prefix}{tag}_{key}"
                out = os.path.join(args.out, name)
                scene = scene_variant(scene_file, args.out, name, turbulence=turb, output=out,
                                      **kw)
                print(f"batch_bench.py: accuracy run {name}", file=sys.stderr)
                runs[key] = landings(lrigid, scene, out)
            acc[tag] = {"float": landing_diff(runs["double"], runs["float"])}
            if "double_half_dt" in runs:
                acc[tag]["dt"] = landing_diff(runs["double"], runs["double_half_dt"])
        return acc

    acc = accuracy(base, "", (False, True))
    leaf_acc = accuracy(leaves, "leaves_", (False,))
    harness = os.path.join(args.build, "bin", "mujoco_harness")
    mujoco = mujoco_pod = None
    if not args.no_peers and os.path.exists(harness):
        mujoco = mujoco_peer(harness, ["--body", "bead"], "the beads", args.quick)
        mujoco_pod = mujoco_peer(harness, [], "the seed pods", args.quick)
    json.dump({"machine": m, "throughput": rows, "accuracy": acc, "peers": peers,
               "mujoco": mujoco, "leaves": {"throughput": leaf_rows, "accuracy": leaf_acc,
                                            "mujoco": mujoco_pod, "all_effects": leaf_all}},
              open(os.path.join(args.out, "batch.json"), "w"), indent=1)
    write_doc(args.doc, m, rows, acc, peers, mujoco, args.quick,
              (leaf_rows, leaf_acc, mujoco_pod, leaf_all))
    print(f"batch_bench.py: wrote {args.doc} (data in {args.out})", file=sys.stderr)


def find_rate(rows, variant, n, t, key="rate"):
    for r in rows:
        if r["variant"] == variant and r["n"] == n and r["threads"] == t:
            return r[key]
    return float("nan")


def throughput_table(rows, handoffs=False):
    lines = ["| N | threads | scalar step | batched, double | batched, float | "
             "batched double / scalar |" + (" steps handed to the scalar step |" if handoffs
                                            else ""),
             "|---|---|---|---|---|---|" + ("---|" if handoffs else "")]
    for n in sorted({r["n"] for r in rows}):
        for t in (1, 2):
            s, d, f = (find_rate(rows, "scalar step, double", n, t),
                       find_rate(rows, "batched, double", n, t),
                       find_rate(rows, "batched, float", n, t))
            line = (f"| {n:,} | {t} | {s / 1e6:.2f} M | {d / 1e6:.2f} M | {f / 1e6:.2f} M "
                    f"| {d / s:.2f} |")
            if handoffs:
                h = find_rate(rows, "batched, double", n, t, "scalar_handoff_fraction")
                line += f" {100 * h:.2f} % |"
            lines.append(line)
    return lines


def accuracy_table(acc, labels):
    lines = ["| scene | compared | landed in both | median | 90th percentile | max |",
             "|---|---|---|---|---|---|"]
    for tag, label in labels:
        for key, what in (("float", "float vs double"), ("dt", "dt 2 ms vs 1 ms (double)")):
            if key not in acc.get(tag, {}):
                continue
            a = acc[tag][key]
            lines.append(f"| {label} | {what} | {a['common']:,} of {a['landed_a']:,} | "
                         f"{a['median']:.2e} m | {a['p90']:.2e} m | {a['max']:.2e} m |")
    return lines


def peer_lines(d, f, peers, of_label, mujoco, mj_label):
    """table rows: each peer's rate and lrigid's batched double (d) and float (f) against it"""
    rates = []
    if peers:
        of = peers["openfoam"]
        rates += [(of_label + ", dispersion off", of["dispersion_off"]),
                  (of_label + ", stochasticDispersionRAS", of["dispersion_on"])]
    if mujoco:
        mj = mujoco["one_body_per_model"]
        rates += [(mj_label + ", RK4", mj["rk4"]), (mj_label + ", Euler", mj["euler"])]
    return [f"| {label} | {r / 1e6:.2f} M | {d / r:.1f} | {f / r:.1f} |" for label, r in rates]


def leaves_section(leaves, peers):
    rows, acc, mujoco_pod, all9 = leaves
    lines = [
        "",
        "## The full leaves model",
        "",
        "`lrigid bench scenes/leaves_wind.json`: 600 leaves (6 x 4 cm, 0.4 mm), 200 paper sheets "
        "(A6) and 200 seed pods (8 x 4 x 4 mm ellipsoids) in the courtyard wind, scaled to N "
        "in these proportions, each type with the scene's own effects (`effects: auto`: "
        "gravity, drag, mean flow, seen turbulence for all; added mass and lift for the flat "
        "ones; splitting, dt = 2 ms). Timed after 0.5 s (250 steps) of warm-up: from rest in "
        "the wind, more of the first steps are stiff. Body-steps per second (wall clock), the "
        "faster of two runs; the last column is the share of the batched steps that a lane "
        "handed to the scalar step:",
        "",
    ]
    lines += throughput_table(rows, handoffs=True)
    lines += ["", f"The full effect set: every effect on every type (`--effects "
              f"{all9['effects']}`: the Basset history and the Magnus force too, and added mass "
              "and buoyancy for the seed pods, which `auto` leaves out as below 1 % of their "
              "forces). Body-steps per second (wall clock; per CPU second in brackets), the "
              "faster of two runs after 250 steps of warm-up; the steps the loops solved by "
              "Newton themselves (stiff drag, or a free Kirchhoff flow whose fixed point does "
              "not contract), and those they handed to the scalar step:", "",
              "| bodies | precision | N | threads | body-steps/s | history and state, bytes/body "
              "| Newton steps | handed to the scalar step |", "|---|---|---|---|---|---|---|---|"]
    labels = {"all": "the whole scene", "plates": "leaves and paper only",
              "pods": "seed pods only"}
    for r in all9["runs"]:
        lines.append(f"| {labels[r['bodies']]} | {r['precision']} | {r['n']} | {r['threads']} | "
                     f"{r['rate'] / 1e6:.2f} M ({r['cpu_rate'] / 1e6:.2f} M) | "
                     f"{r['bytes_per_body']:.0f} | {100 * r['newton_fraction']:.2f} % | "
                     f"{100 * r['scalar_handoff_fraction']:.2f} % |")
    d = find_rate(rows, "batched, double", 10000, 1, "cpu_rate")
    f = find_rate(rows, "batched, float", 10000, 1, "cpu_rate")
    s = find_rate(rows, "scalar step, double", 10000, 1, "cpu_rate")
    lines += ["", "Against the peers of this run, per core (per CPU second, one thread, N = 10^4):",
              "", "| | per core | lrigid batched double / it | lrigid batched float / it |",
              "|---|---|---|---|",
              f"| lrigid scalar step | {s / 1e6:.2f} M | {d / s:.1f} | {f / s:.1f} |"]
    lines += peer_lines(d, f, peers, "OpenFOAM parcels", mujoco_pod, "MuJoCo 2.2, the seed pods")
    lines += ["", "The OpenFOAM parcels are point spheres (drag and gravity); lrigid's leaves "
              "are rigid plates with added mass, the Kirchhoff equations, APW drag, torque and "
              "lift. MuJoCo steps the scene's seed pods (`mujoco_harness`, its default body: "
              "free ellipsoids with `fluidshape=\"ellipsoid\"`, contacts off, a uniform 5 m/s "
              "wind, one body per model); lrigid the whole scene.", "",
              "What single precision costs on the leaves scene (1,000 bodies, up to 20 s, "
              "landing points; without turbulence: `art.turbulence_scale = 0`). Tumbling plates "
              "are chaotic even in a steady wind, so a rounding difference can send a leaf "
              "elsewhere: compare the float column with the time-step one.", ""]
    lines += accuracy_table(acc, (("det", "leaves, no turbulence"),))
    return lines


BEGIN = "<!-- batch-bench begin (generated by bench/perf/batch_bench.py; do not edit) -->"
END = "<!-- batch-bench end -->"


def write_doc(path, m, rows, acc, peers, mujoco, quick, leaves=None):
    def rate(variant, n, t, key="rate"):
        return find_rate(rows, variant, n, t, key)

    lines = [
        BEGIN,
        "",
        f"Measured {m['date']} on {m['cpu']} ({m['cores']} cores), commit {m['commit']}, "
        f"load before {m['load']}{' (--quick: short runs)' if quick else ''}.",
        "",
        "Body types take a batched step (`runtime/src/integrate/rigid_batch.h`): blocks of 32 "
        "bodies of one type, structure of arrays, each stage one loop across the block that the"
        " compiler vectorizes, the field sampled once per step. Its loops are compiled once for "
        "each kind of mass matrix: isotropic (uniform spheres: the free Kirchhoff flow is a "
        "rotation alone and the lanes keep the world velocity), diagonal (plates and ellipsoids:"
        " leaves, paper, seed pods; the Kirchhoff implicit midpoint iterated per lane under a "
        "convergence mask) and full 6 x 6 (meshes: an artist's curled leaf; "
        "`bench/perf/mesh_leaf_bench.py`: a mesh leaf costs 1.3-1.45 times a box leaf with "
        "`splitting` and `strang` in the courtyard grid and in uniform wind, 1.1 times with "
        "`euler` and `rk4` in the grid, docs/performance.md). Every effect is batched, the "
        "Basset history (kept by the block driver, its current interval a mass in the implicit "
        "solve) and the Magnus force included. A body whose centre of mass is off its volume "
        "centroid (`mass_offset`: a keel, a weighted stem; a sphere too, whose loops then are "
        "those of a diagonal or full mass matrix): the fluid's forces act at the centroid, "
        "moving at v + ω × r_cob, and they and the buoyancy turn the body about its centre of "
        "mass (runtime factors in the loops, zero for a uniform body, as for Magnus and Basset; "
        "`RigidBatch.BodiesWithTheirCentreOfMassOffTheCentroidMatchTheScalarStep`: leaves, seed"
        " pods, a leaf without added mass and a sphere, each scheme: positions within 10⁻¹³ m "
        "and spins within 10⁻⁹ rad/s of the scalar step after 0.2 s). The loops run the scalar "
        "step's Newton iterations themselves (stiff drag; a Kirchhoff fixed point that does not"
        " contract); a lane hands its step to the scalar step only where Newton struggles (the "
        "scalar step then substeps) or the scene rules the batched step out. The physics is the"
        " scalar step's, term for term, for each scheme (`euler` and `rk4` too: "
        "docs/physics/integrators.md); `tests/runtime/integrate/sphere_batch_test.cpp` and "
        "`rigid_batch_test.cpp` hold it to the scalar step to 1e-9 (1e-8 for tumbling leaves,"
" whose chaos amplifies rounding). Scenes choose a step per body type automatically "
        "(`lrigid explain` says which); `\"integrator\": {\"batched\": false}` turns it off and "
        "`\"precision\": \"float\"` runs it in single precision (docs/scene-format.md).",
        "",
        "## Throughput",
        "",
        "`lrigid bench scenes/beads_wind.json` (500 um glass beads in the courtyard wind: "
        "gravity, buoyancy, drag, added mass, mean flow, seen turbulence; splitting, dt = 2 ms), "
        "body-steps per second (wall clock), the faster of two runs:",
        "",
    ]
    lines += throughput_table(rows)
    if peers:
        lines += [
            "",
            "## Against the peers, same run",
            "",
            "OpenFOAM's `icoUncoupledKinematicParcelFoam` (v1912) tracking the same 10,000 beads "
            "through the same steady field (`bench/peers/run_peers.sh --skip-mujoco`: sphereDrag "
            "and gravity, dt = 2 ms, 200 steps, steady-state stepping, no writes), against "
            "lrigid's batched step on `scenes/beads_wind.json`, which does more per step (added "
            "mass, buoyancy and the seen-velocity Langevin model with Thomson's drift in every "
            "run). Per core: body- or parcel-steps per CPU second, one process, one thread; the "
            "faster of two runs each.",
            "",
            "| | per core | lrigid batched double / it | lrigid batched float / it |",
            "|---|---|---|---|",
        ]
        d = rate("batched, double", 10000, 1, "cpu_rate")
        f = rate("batched, float", 10000, 1, "cpu_rate")
        s = rate("scalar step, double", 10000, 1, "cpu_rate")
        lines.append(f"| lrigid scalar step | {s / 1e6:.2f} M | {d / s:.1f} | {f / s:.1f} |")
        lines += peer_lines(d, f, peers, "OpenFOAM", mujoco, "MuJoCo 2.2 ellipsoid fluid model")
        lines += ["", f"OpenFOAM measured {peers.get('date', '?')}, "
                  f"load {peers.get('load', '?')}."]
        if mujoco:
            lines += ["", "MuJoCo (`bench/peers/mujoco_harness --body bead`): the same beads as "
                      "free spheres with `fluidshape=\"ellipsoid\"`, contacts off, in a 5 m/s "
                      "uniform wind (MuJoCo has no field to sample and no turbulence model), one "
                      "body per model (its best case: a model of many bodies costs it "
                      "O(bodies²) per step)."]
    lines += [
        "",
        "## What single precision costs",
        "",
        "Landing points (x, y) after up to 10 s of flight, 10,000 beads, float against double; "
        "beside it, for scale, the time-step error of the double run (dt = 2 ms against 1 ms) on "
        "the same scene without turbulence. With turbulence any perturbation (a rounding, a "
        "different time step) moves a bead onto another path of the chaotic flow around the "
        "buildings, so there only the statistics of the two runs can agree.",
        "",
    ]
    lines += accuracy_table(acc, (("det", "no turbulence"), ("turb", "with turbulence")))
    if leaves:
        lines += leaves_section(leaves, peers)
    lines += ["", END]
    block = "\n".join(lines)
    # only the part between the markers is this script's: the page's other sections (the
    # time-dependent fields of series_cost.py, hand-written notes) stay as they are
    text = open(path).read() if os.path.exists(path) else ""
    a, b = text.find(BEGIN), text.find(END)
    if a >= 0 and b > a:
        text = text[:a] + block + text[b + len(END):]
    else:
        text = "# The batched steps\n\n" + block + "\n"
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


if __name__ == "__main__":
    main()
