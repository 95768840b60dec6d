#!/usr/bin/python3
"""What a leaf from a mesh costs against the box leaf: the leaves scene's leaf entry
(scenes/leaves_wind.json: 6 x 4 cm, 0.4 mm, 600 kg/m^3, the scene's "auto" effects) stepped by
`lrigid bench` once as the box and once as tests/data/meshes/bent_leaf.obj (the same leaf curled
4 mm and turned 20 degrees about z, 1696 triangles: its generalized mass is a full 6 x 6, which
the batched step runs on the full-mass kernels of model/kirchhoff.h). Body-steps per CPU
second, the two measured alternately --rounds times, best of each (other jobs only slow a run
down), and their ratio. --scalar also steps the mesh on the scalar step (the scene with
"batched": false, 1e6 body-steps timed) and prints the batched step's gain over it.

    bench/perf/mesh_leaf_bench.py [--lrigid build/bin/lrigid] [--n 10000] [--rounds 3]
        [--integrators splitting,strang] [--threads 1] [--warmup 250] [--scalar] [--uniform]
        [--json OUT]

Field: results/grids/windCourtyard.vti when ./Allrun made it, else a uniform wind of 3 m/s with
seen turbulence (k = 0.1 m^2/s^2, eps = 0.05 m^2/s^3), said in the output; --uniform takes the
uniform wind anyway. Warm-up steps first
(0.5 s at the scene's 2 ms): the leaves are released at rest and start tumbling.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def leaf_scene(out_dir, mesh, batched=True, uniform=False):
    s = json.load(open(os.path.join(ROOT, "scenes/leaves_wind.json")))
    grid = os.path.join(ROOT, "results/grids/windCourtyard.vti")
    if os.path.exists(grid) and not uniform:
        s["fluid"]["field"] = grid
        field = "windCourtyard.vti (the leaves scene's grid)"
    else:
        s["fluid"].pop("field", None)
        s["fluid"]["uniform"] = {"U": [3.0, 0.0, 0.0], "k": 0.1, "epsilon": 0.05}
        field = ("uniform wind 3 m/s, k 0.1 m^2/s^2, eps 0.05 m^2/s^3" +
                 (" (--uniform)" if uniform else " (no windCourtyard.vti)"))
    leaf = [b for b in s["bodies"] if b["name"] == "leaf"][0]
    if mesh:
        leaf["name"] = "mesh_leaf"
        leaf["shape"] = {"type": "mesh",
                         "file": os.path.join(ROOT, "tests/data/meshes/bent_leaf.obj")}
    s["bodies"] = [leaf]
    if not batched:
        s.setdefault("integrator", {})["batched"] = False
    path = os.path.join(out_dir, ("mesh" if mesh else "box") + "_leaf" +
                        ("" if batched else "_scalar") + ".json")
    json.dump(s, open(path, "w"), indent=1)
    return path, field


def bench(lrigid, scene, args, extra=()):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([lrigid, "bench", scene, "--n", str(args.n), "--integrators",
                        args.integrators, "--threads", str(args.threads), "--warmup",
                        str(args.warmup), "--quiet", "--json", out.name] + list(extra),
                       check=True)
        return json.load(open(out.name))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lrigid", default=os.path.join(ROOT, "build/bin/lrigid"))
    ap.add_argument("--n", type=int, default=10000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--integrators", default="splitting,strang")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--warmup", type=int, default=250)
    ap.add_argument("--scalar", action="store_true",
                    help="also the mesh on the scalar step (\"batched\": false)")
    ap.add_argument("--uniform", action="store_true",
                    help="the uniform wind even where windCourtyard.vti exists (no grid "
                         "sampling: the mass's arithmetic weighs more)")
    ap.add_argument("--json")
    args = ap.parse_args()
    best = {}
    with tempfile.TemporaryDirectory() as tmp:
        box, field = leaf_scene(tmp, False, uniform=args.uniform)
        mesh, _ = leaf_scene(tmp, True, uniform=args.uniform)
        kinds = [("box", box, ()), ("mesh", mesh, ())]
        if args.scalar:
            kinds.append(("scalar", leaf_scene(tmp, True, False, args.uniform)[0],
                          ("--body-steps", "1000000")))
        print("field: " + field)
        for r in range(args.rounds):
            for kind, scene, extra in kinds:
                res = bench(args.lrigid, scene, args, extra)
                for run in res["runs"]:
                    key = (kind, run["integrator"])
                    rate = run["body_steps_per_cpu_s"]
                    prev = best.get(key)
                    if prev is None or rate > prev["rate"]:
                        best[key] = {"rate": rate, "scalar_pct":
                                     100.0 * run["scalar_handoffs"] / max(1, run["body_steps"]),
                                     "newton": run["newton_steps"]}
    machine = "%s, %s, %d CPUs" % (platform.node(), platform.processor() or platform.machine(),
                                   os.cpu_count())
    cpu = ""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    print("%s; %s; %s" % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), cpu, machine))
    print("N = %d, %d thread(s), %d warm-up steps, best of %d rounds, body-steps per CPU second"
          % (args.n, args.threads, args.warmup, args.rounds))
    print("%-10s %14s %14s %10s %12s" % ("scheme", "box leaf", "mesh leaf", "cost ratio",
                                          "mesh scalar%") +
          (" %14s %10s" % ("mesh, scalar", "gain") if args.scalar else ""))
    out = {"field": field, "n": args.n, "threads": args.threads, "cpu": cpu,
           "date": time.strftime("%Y-%m-%d", time.gmtime()), "schemes": {}}
    for integ in args.integrators.split(","):
        b, m = best[("box", integ)], best[("mesh", integ)]
        ratio = b["rate"] / m["rate"] if m["rate"] > 0 else float("inf")
        line = "%-10s %14.4g %14.4g %10.2f %12.2f" % (integ, b["rate"], m["rate"], ratio,
                                                      m["scalar_pct"])
        out["schemes"][integ] = {"box": b, "mesh": m, "cost_ratio": ratio}
        if args.scalar:
            sc = best[("scalar", integ)]
            gain = m["rate"] / sc["rate"] if sc["rate"] > 0 else float("inf")
            line += " %14.4g %10.2f" % (sc["rate"], gain)
            out["schemes"][integ].update({"mesh_scalar": sc, "batched_over_scalar": gain})
        print(line)
    if args.json:
        json.dump(out, open(args.json, "w"), indent=1)


if __name__ == "__main__":
    sys.exit(main())
