#!/usr/bin/python3
"""What a time-dependent field (a .pvd series) costs the batched step, against the same scene on
one of its frames (the target: at most 1.3x). Run after ./Allrun -all (results/grids/tankJet.pvd):

    bench/perf/series_cost.py [--lrigid build/bin/lrigid] [--rounds 3] [--n 4000]
        [--body-steps 2e6] [--write]

The tank scene (scenes/debris_tank.json, splitting at 2 ms) is benched for --body-steps
body-steps from t = 0, one thread, per CPU-second, the variants alternately (the best of
--rounds kept), each with its field swapped for:
  series       the tank's series, its times shifted so that the first frame is at t = 0: every
               step blends two frames (the scene's own series is clamped to its first frame
               before t = 0.5 s, which a short bench would not leave);
  same-frame   the same times, every entry the middle frame's file: the flow of `frame-mid`
               exactly, so the ratio to it is the cost of blending two frames and nothing else;
  frame-first, frame-second, frame-mid   single .vti frames (steady fields).
The shifted series files are written beside the grid (results/grids/.series_cost_*.pvd) and the
scene copies beside scenes/, and removed afterwards. --write puts the table into
docs/batched-step.md (between the series-cost markers), with the machine, date and load.
"""
import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GRIDS = os.path.join(ROOT, "results", "grids")
SCENE = os.path.join(ROOT, "scenes", "debris_tank.json")
DOC = os.path.join(ROOT, "docs", "batched-step.md")
BEGIN, END = "<!-- series-cost begin -->", "<!-- series-cost end -->"


def bench(lrigid, scene, n, body_steps):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([lrigid, "bench", scene, "--n", str(n), "--threads", "1",
                        "--integrators", "splitting", "--effects", "auto", "--body-steps",
                        str(body_steps), "--min-steps", "10", "--warmup", "2", "--quiet",
                        "--json", out.name], check=True)
        return json.load(open(out.name))["runs"][0]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lrigid", default=os.path.join(ROOT, "build", "bin", "lrigid"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--n", type=int, default=4000)
    ap.add_argument("--body-steps", type=float, default=2e6)
    ap.add_argument("--write", action="store_true")
    a = ap.parse_args()
    pvd = os.path.join(GRIDS, "tankJet.pvd")
    if not os.path.exists(pvd):
        sys.exit("series_cost.py: results/grids/tankJet.pvd missing (./Allrun -all)")
    text = open(pvd).read()
    entries = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)
    if len(entries) < 3:
        sys.exit(f"series_cost.py: {pvd}: fewer than 3 frames")
    t0 = float(entries[0][0])
    mid = entries[len(entries) // 2][1]
    shifted = re.sub(r'timestep="([^"]+)"', lambda m: f'timestep="{float(m.group(1)) - t0:.17g}"',
                     text)
    same = re.sub(r'file="[^"]+"', f'file="{mid}"', shifted)
    made = []

    def write(path, content):
        with open(path, "w") as f:
            f.write(content)
        made.append(path)
        return path

    try:
        series_file = write(os.path.join(GRIDS, ".series_cost_series.pvd"), shifted)
        same_file = write(os.path.join(GRIDS, ".series_cost_same.pvd"), same)
        base = json.load(open(SCENE))
        variants = {"series": series_file, "same-frame": same_file,
                    "frame-first": os.path.join(GRIDS, entries[0][1]),
                    "frame-second": os.path.join(GRIDS, entries[1][1]),
                    "frame-mid": os.path.join(GRIDS, mid)}
        scenes = {}
        for name, field in variants.items():
            s = json.loads(json.dumps(base))
            s["fluid"]["field"] = os.path.relpath(field, os.path.dirname(SCENE))
            scenes[name] = write(os.path.join(os.path.dirname(SCENE), f".series_cost_{name}.json"),
                                 json.dumps(s))
        best = {k: None for k in scenes}
        for _ in range(a.rounds):
            for name, path in scenes.items():
                r = bench(a.lrigid, path, a.n, a.body_steps)
                if best[name] is None or r["body_steps_per_cpu_s"] > best[name]["body_steps_per_cpu_s"]:
                    best[name] = r
    finally:
        for p in made:
            if os.path.exists(p):
                os.unlink(p)
    rate = {k: v["body_steps_per_cpu_s"] for k, v in best.items()}
    what = {"series": f"the series from its first frame ({len(entries)} frames, every step blends two)",
            "same-frame": f"a series of {len(entries)} copies of `{os.path.basename(mid)}`",
            "frame-first": f"`{os.path.basename(entries[0][1])}` alone",
            "frame-second": f"`{os.path.basename(entries[1][1])}` alone",
            "frame-mid": f"`{os.path.basename(mid)}` alone"}
    lines = ["| field | body-steps per CPU-second | handed to the scalar step | Newton steps |",
             "|---|---|---|---|"]
    for k in scenes:
        r = best[k]
        lines.append(f"| {what[k]} | {rate[k] / 1e6:.2f} M | {r['scalar_handoffs']} | "
                     f"{r['newton_steps']} |")
    blend_cost = rate["frame-mid"] / rate["same-frame"]
    lo = min(rate["frame-first"], rate["frame-second"])
    hi = max(rate["frame-first"], rate["frame-second"])
    load = os.getloadavg()[0]
    stamp = (f"{platform.node()}, {os.cpu_count()} cores, "
             f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, load {load:.1f}; "
             f"`bench/perf/series_cost.py --rounds {a.rounds} --n {a.n} "
             f"--body-steps {a.body_steps:g}`")
    summary = (f"Blending two frames costs **{blend_cost:.2f}x** the same flow as one frame "
               f"(same-frame against `{os.path.basename(mid)}` alone). The real series, "
               f"between its first two frames, runs at {rate['series'] / 1e6:.2f} M "
               f"body-steps/CPU-s, between those two frames alone ({lo / 1e6:.2f}-"
               f"{hi / 1e6:.2f} M): what a step costs follows the flow (the Newton steps of stiff "
               f"drag), not the blend.")
    table = "\n".join(lines)
    print(table)
    print()
    print(summary)
    print(stamp)
    if a.write:
        doc = open(DOC).read()
        block = f"{BEGIN}\n{table}\n\n{summary}\n\nMeasured: {stamp}.\n{END}"
        if BEGIN in doc:
            doc = re.sub(re.escape(BEGIN) + ".*?" + re.escape(END), lambda m: block, doc,
                         flags=re.S)
        else:
            doc = doc.rstrip("\n") + "\n\n## Time-dependent fields (.pvd series)\n\n" + block + "\n"
        tmp = DOC + ".tmp"
        with open(tmp, "w") as f:
            f.write(doc)
        os.replace(tmp, DOC)
    return 0


if __name__ == "__main__":
    sys.exit(main())
