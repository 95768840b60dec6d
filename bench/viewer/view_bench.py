#!/usr/bin/python3
"""Speed of `lrigid view` (docs/viewer.md): frames per second and simulation rate with
10^3, 10^4 and 10^5 bodies, drawn under Xvfb's software OpenGL, against the simulation alone.

For each body count N the scene's bodies are scaled to N in all (same proportions), then:
  alone     `lrigid bench SCENE --n N --threads T --integrators <scene's>`: body-steps/s
  fast      `lrigid view --pace fast`: frames/s, body-steps/s while stepping, x real time
  realtime  `lrigid view --pace realtime`: does simulated time keep the wall clock (x1.00)?
Real time needs N / dt body-steps/s. Each view run draws --frames frames (fewer for 10^5);
the numbers are those of the summary line `lrigid view` prints at exit.

  bench/viewer/view_bench.py [--scene scenes/leaves_wind.json] [--uniform] [--n 1000,10000,100000]
                             [--threads 1] [--seconds 12] [--out table.md]
--uniform replaces the scene's grid with a uniform wind (3 m/s, k 0.5, eps 0.2) when the grid
of the scene has not been made (./Allrun makes it)."""
import argparse, json, os, re, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def scaled_scene(src, n, uniform, tmp):
    s = json.load(open(src))
    if uniform:
        s["fluid"].pop("field", None)
        s["fluid"]["uniform"] = {"U": [3.0, 0.0, 0.0], "k": 0.5, "epsilon": 0.2}
    else:
        f = s["fluid"]["field"]
        if not os.path.isabs(f):
            s["fluid"]["field"] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(src)), f))
    total = sum(b["count"] for b in s["bodies"])
    left = n
    for i, b in enumerate(s["bodies"]):
        b["count"] = left if i == len(s["bodies"]) - 1 else max(1, round(b["count"] * n / total))
        left -= b["count"]
    s["output"] = {"dir": os.path.join(tmp, "out"), "every": 1.0, "formats": ["csv"]}
    path = os.path.join(tmp, f"scene_{n}.json")
    json.dump(s, open(path, "w"), indent=1)
    return path, s["integrator"]["scheme"], s["integrator"]["dt"]


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"view_bench: failed ({p.returncode}): {' '.join(cmd)}\n{p.stdout}{p.stderr}")
    return p.stdout + p.stderr


def view(lrigid, scene, pace, frames, threads):
    out = run(["xvfb-run", "-a", "-s", "-screen 0 1280x720x24", lrigid, "view", scene,
               "--pace", pace, "--frames", str(frames), "--threads", str(threads)])
    m = re.search(r"view: (\d+) frames in ([0-9.]+) s \(([0-9.]+) frames/s\); simulated ([0-9.]+) s "
                  r"\(x([0-9.]+) of real time\); (\d+) body-steps, ([0-9.e+]+) body-steps/s while "
                  r"stepping, stepping (\d+)%", out)
    if not m:
        sys.exit(f"view_bench: no summary line in:\n{out}")
    return {"fps": float(m[3]), "x": float(m[5]), "rate": float(m[7]), "busy": int(m[8]),
            "wall": float(m[2])}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes/leaves_wind.json"))
    ap.add_argument("--uniform", action="store_true")
    ap.add_argument("--n", default="1000,10000,100000")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--frames", default="150,60,8", help="frames drawn per body count")
    ap.add_argument("--lrigid", default=os.path.join(ROOT, "build/bin/lrigid"))
    ap.add_argument("--out")
    a = ap.parse_args()
    ns = [int(x) for x in a.n.split(",")]
    frames = [int(x) for x in a.frames.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n, f in zip(ns, frames + frames[-1:] * len(ns)):
            scene, scheme, dt = scaled_scene(a.scene, n, a.uniform, tmp)
            out = run([a.lrigid, "bench", scene, "--n", str(n), "--threads", str(a.threads),
                       "--integrators", scheme])
            line = [l for l in out.splitlines() if l.split()[:1] == [str(n)]][-1].split()
            alone, alone_cpu = float(line[5]), float(line[7])
            fast = view(a.lrigid, scene, "fast", f, a.threads)
            real = view(a.lrigid, scene, "realtime", f, a.threads)
            rows.append((n, n / dt, alone, alone_cpu, fast, real, os.getloadavg()[0]))
            print(f"{n}: alone {alone:.3g} body-steps/s (x{alone * dt / n:.2f} real time); "
                  f"fast {fast}; realtime {real}", file=sys.stderr)
    lines = ["| bodies | body-steps/s for real time | simulation alone: body-steps/s wall (per CPU s) | "
             "view fast: frames/s | view fast: body-steps/s while stepping, x real time | "
             "view realtime: frames/s | view realtime: x real time (stepping % of wall) | load avg |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for n, need, alone, alone_cpu, fast, real, load in rows:
        lines.append(f"| {n:,} | {need:.3g} | {alone:.3g} (x{alone / need:.2f}) ({alone_cpu:.3g}) | "
                     f"{fast['fps']:.1f} | {fast['rate']:.3g}, x{fast['x']:.2f} | {real['fps']:.1f} | "
                     f"x{real['x']:.2f} ({real['busy']} %) | {load:.1f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if a.out:
        open(a.out, "w").write(text)


if __name__ == "__main__":
    main()
