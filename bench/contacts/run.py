#!/usr/bin/python3
"""Cost of contacts on the leaves scene, in instructions (callgrind).

The same scene is run twice: with contacts (scenes/leaves_wind.json as it is: ground and walls
"collide") and without (ground.contact "stop", walls.contact "stop": the seed's behaviour, a
body stops where it first touches a surface). Three figures, because one alone is not fair:

1. in flight: `lrigid bench` on the scene (bodies in its spawn box, 14-20 m up, far from every
   surface, 40 steps): what a body far from surfaces pays for contacts being on (the one
   comparison per surface of the batched step). `simulate` inclusive, both modes.
2. per body-step over a whole run (`lrigid run`, N bodies, the scene's duration, csv every 5 s):
   `simulate` inclusive / the run's body-steps. With "collide" a body on the ground keeps being
   stepped while it slides or rests (until it sleeps or leaves); with "stop" it stops at its
   first touchdown, so this ratio weighs the steps on surfaces (each with its contact pass) at
   their share of the run.
3. the whole run: `simulate` inclusive of both runs. Its ratio also counts the steps the
   bodies on surfaces take at all (sliding leaves are stepped; stopped ones are not): that is
   what the user pays for bodies that move on after touchdown, not the contact code's cost.

Writes bench/contacts/contacts_cost.md (copied into docs/performance.md by
bench/perf/make_report.py, and into its "Contacts" section here) with the machine, the date,
the load and the commands. Usage: bench/contacts/run.py [--bin build/bin/lrigid] [--n 200]
[--out /tmp/lrigid_contacts_bench] [--no-docs]
"""
import argparse
import datetime
import json
import os
import platform
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "lib"))
from callgrind_count import callgrind, inclusive_table, instructions_of  # noqa: E402

# measure 2's difference by part: (key, the functions' symbols); the first three do not call one
# another, so with the rest of `simulate` they split it
PARTS = (("step", r"(splitting|strang|euler|rk4)_lanes<"),
         ("contact", r"lrigid::contact_after_step\("), ("watch", r"lrigid::watch_sleeper\("),
         ("sample", r"sample_lanes<"))
PART_NAMES = {
    "step": "the batched steps' loops (`splitting_lanes`, `strang_lanes`, `euler_lanes`, "
            "`rk4_lanes`, every variant; with the samples they take)",
    "contact": "the contact pass (`contact_after_step`)",
    "watch": "the sleepers' gust watches (`watch_sleeper`)",
    "rest": "the rest of `simulate` (block driver, samples taken again after a contact, hand-offs)",
    "sample": "of these, the lanes' samples (`sample_lanes`, in the steps and after contacts)",
}
BEGIN = "<!-- contacts-cost:begin (bench/contacts/run.py; do not edit) -->"
END = "<!-- contacts-cost:end -->"


def load():
    return " ".join(open("/proc/loadavg").read().split()[:3])


def cpu_name():
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return platform.processor()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin", "lrigid"))
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "leaves_wind.json"))
    ap.add_argument("--grid", default=os.path.join(ROOT, "results", "grids", "windCourtyard.vti"))
    ap.add_argument("--n", type=int, default=200, help="bodies of the whole runs")
    ap.add_argument("--out", default="/tmp/lrigid_contacts_bench")
    ap.add_argument("--no-docs", action="store_true", help="write contacts_cost.md only")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    base = json.load(open(a.scene))
    base["fluid"]["field"] = os.path.abspath(a.grid)
    total = sum(b["count"] for b in base["bodies"])
    load0 = load()
    rows = {}
    for mode in ("collide", "stop"):
        s = json.loads(json.dumps(base))
        s["ground"]["contact"] = mode
        s["walls"] = {"contact": mode}
        # the whole run: n bodies in the scene's proportions
        for b in s["bodies"]:
            b["count"] = max(1, round(b["count"] * a.n / total))
        s["output"] = {"dir": os.path.join(a.out, "run_" + mode), "every": 5.0,
                       "formats": ["csv"]}
        path = os.path.join(a.out, "scene_%s.json" % mode)
        json.dump(s, open(path, "w"), indent=1)
        run_i = callgrind([a.bin, "run", path, "--threads", "1"],
                          os.path.join(a.out, "cg_run_%s.out" % mode))
        summ = json.load(open(os.path.join(s["output"]["dir"], "summary.json")))
        bench_i = callgrind([a.bin, "bench", path, "--n", "1000", "--threads", "1",
                             # the scene's own scheme, as in measures 2 and 3
                             "--integrators", s["integrator"]["scheme"], "--effects", "auto",
                             "--body-steps", "1",
                             "--min-steps", "40", "--warmup", "0", "--quiet"],
                            os.path.join(a.out, "cg_bench_%s.out" % mode))
        table = inclusive_table(os.path.join(a.out, "cg_run_%s.out" % mode))
        rows[mode] = {"run": run_i, "steps": summ["body_steps"], "bench": bench_i,
                      "states": summ.get("states", {}),
                      "parts": {key: instructions_of(table, pat) for key, pat in PARTS}}
    c, s = rows["collide"], rows["stop"]
    per_c, per_s = c["run"] / c["steps"], s["run"] / s["steps"]
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    L = []
    w = L.append
    w("Measured by `bench/contacts/run.py --n %d` at %s (commit %s), %s, %d cores, load %s "
      "(start) / %s (end); instructions counted by callgrind (`simulate` inclusive, 1 thread), "
      "so the load does not change them." % (a.n, now, commit, cpu_name(), os.cpu_count(), load0,
                                             load()))
    w("")
    w("| measure | with contacts (collide) | without (stop) | ratio |")
    w("|---|---|---|---|")
    w("| 1. in flight: `lrigid bench SCENE --n 1000 --threads 1 --integrators %s "
      "--effects auto --body-steps 1 --min-steps 40 --warmup 0` (spawn box 14-20 m up) | "
      "%.1f M instr | %.1f M instr | **%.3fx** |" % (base["integrator"]["scheme"],
                                                     c["bench"] / 1e6, s["bench"] / 1e6,
                                                     c["bench"] / s["bench"]))
    w("| 2. per body-step, whole run (`lrigid run`, %d bodies, %g s) | %.0f M / %.3f M = %.0f "
      "instr | %.0f M / %.3f M = %.0f instr | **%.2fx** |" %
      (sum(b["count"] for b in json.load(open(os.path.join(a.out, "scene_stop.json")))["bodies"]),
       base["duration"], c["run"] / 1e6, c["steps"] / 1e6, per_c, s["run"] / 1e6,
       s["steps"] / 1e6, per_s, per_c / per_s))
    w("| 3. whole run, `simulate` | %.0f M instr (%d body-steps) | %.0f M instr (%d body-steps)"
      " | **%.2fx** |" % (c["run"] / 1e6, c["steps"], s["run"] / 1e6, s["steps"],
                           c["run"] / s["run"]))
    w("")
    w("Measure 2 by part (callgrind inclusive instructions of the whole runs, per body-step of "
      "each run):")
    w("")
    w("| part | with contacts | without | difference |")
    w("|---|---|---|---|")
    for r in (c, s):
        r["parts"]["rest"] = r["run"] - r["parts"]["step"] - r["parts"]["contact"] - \
            r["parts"]["watch"]
    for key in ("step", "contact", "watch", "rest", "sample"):
        pc, ps = c["parts"][key] / c["steps"], s["parts"][key] / s["steps"]
        w("| %s | %.0f | %.0f | %+.0f |" % (PART_NAMES[key], pc, ps, pc - ps))
    w("")
    w("Final states with contacts: %s; without: %s." %
      (", ".join("%s %d" % kv for kv in sorted(c["states"].items()) if kv[1]),
       ", ".join("%s %d" % kv for kv in sorted(s["states"].items()) if kv[1])))
    body = "\n".join(L)
    md = os.path.join(HERE, "contacts_cost.md")
    with open(md + ".tmp", "w") as f:
        f.write("## Contacts\n\n" + BEGIN + "\n" + body + "\n" + END + "\n")
    os.replace(md + ".tmp", md)
    print(body)
    if a.no_docs:
        return
    for doc, head in ((os.path.join(ROOT, "docs", "performance.md"), "## Contacts"),
                      (os.path.join(ROOT, "docs", "contacts.md"), None)):
        text = open(doc).read()
        i, j = text.find(BEGIN), text.find(END)
        if i >= 0 and j > i:
            text = text[:i] + BEGIN + "\n" + body + "\n" + text[j:]
        elif head:
            text = text.rstrip("\n") + "\n\n" + head + "\n\n" + BEGIN + "\n" + body + "\n" + END + "\n"
        else:
            sys.exit("run.py: %s has no %s ... %s markers" % (doc, BEGIN, END))
        with open(doc + ".tmp", "w") as f:
            f.write(text)
        os.replace(doc + ".tmp", doc)


if __name__ == "__main__":
    main()
