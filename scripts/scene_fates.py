#!/usr/bin/python3
"""Per body type of an `lrigid run` output directory: how many bodies landed, exited, failed or
were still moving at the end, and their descent: the median over bodies of the mean descent
speed (initial z − last written z) / (time of landing, exit or the end of the run), m/s (landings
from landings.csv, exits and failures from summary.json).

    scripts/scene_fates.py RUN_DIR [RUN_DIR ...]

Reads RUN_DIR/summary.json and RUN_DIR/trajectories.csv (the csv output format is needed).
"""
import csv
import json
import os
import sys
from statistics import median


def fates(run):
    with open(os.path.join(run, "summary.json")) as f:
        summ = json.load(f)
    stop = {s["body"]: s for s in summ.get("stopped", [])}
    lp = os.path.join(run, "landings.csv")
    if os.path.exists(lp):
        with open(lp) as f:
            for row in csv.DictReader(f):
                stop[int(row["body"])] = dict(status="landed", t=float(row["t"]))
    first, last, typ = {}, {}, {}
    path = os.path.join(run, "trajectories.csv")
    if not os.path.exists(path):
        sys.exit("scene_fates.py: %s: no trajectories.csv (add \"csv\" to output.formats)" % run)
    with open(path) as f:
        for row in csv.DictReader(f):
            b = int(row["body"])
            typ[b] = row["type"]
            rec = (float(row["t"]), float(row["z"]))
            first.setdefault(b, rec)
            last[b] = rec
    out = {}
    for b, name in typ.items():
        o = out.setdefault(name, dict(n=0, landed=0, exited=0, failed=0, moving=0, speeds=[]))
        o["n"] += 1
        st = stop.get(b)
        status = st["status"] if st else "moving"
        o[status if status in o else "moving"] += 1
        t_end = st["t"] if st else last[b][0]
        if t_end > first[b][0]:
            o["speeds"].append((first[b][1] - last[b][1]) / (t_end - first[b][0]))
    return summ, out


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for run in sys.argv[1:]:
        summ, out = fates(run)
        print("%s: %d bodies, landed %d, exited %d, failed %d" % (
            run, summ["bodies"], summ["landed"], summ["exited"], summ["failed"]))
        for name, o in out.items():
            print("  %-10s n=%4d landed %4d exited %4d failed %d moving %4d  median mean descent "
                  "%.3f m/s" % (name, o["n"], o["landed"], o["exited"], o["failed"], o["moving"],
                               median(o["speeds"]) if o["speeds"] else float("nan")))


if __name__ == "__main__":
    main()
