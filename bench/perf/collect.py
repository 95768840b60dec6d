#!/usr/bin/python3
"""Collects the runs of bench/perf/stream_bench.sh and scaling_bench.sh into one JSON file each
(read by bench/perf/make_report.py). Each run is a `/usr/bin/time -v` log and the run's
summary.json; the fastest run of each configuration is kept.

  collect.py stream DST SERIES THREADS LOAD_BEFORE LOAD_AFTER "MODE TIME_LOG SUMMARY"...
  collect.py scaling DST N STEPS MAX_CORES LOAD_BEFORE LOAD_AFTER
             "R T TIME_LOG SUMMARY TIME_LOG_2 SUMMARY_2"...  (runs of STEPS and 2 x STEPS steps)
"""
import json
import os
import re
import sys
import time
import xml.etree.ElementTree as ET


def timev(path):
    """wall s, CPU (user + sys) s and peak RSS bytes from a /usr/bin/time -v log"""
    t = open(path).read()
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", t)
    if not m:
        sys.exit("collect.py: %s: no /usr/bin/time -v figures" % path)
    wall = 0.0
    for part in m.group(1).split(":"):
        wall = 60 * wall + float(part)
    cpu = sum(float(x) for x in re.findall(r"(?:User|System) time \(seconds\): (\S+)", t))
    rss = 1024 * int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t).group(1))
    return wall, cpu, rss


def header(load_before, load_after):
    cpu = re.search(r"model name\s*: (.*)", open("/proc/cpuinfo").read()).group(1)
    return {"date": time.strftime("%Y-%m-%d %H:%M", time.gmtime()),
            "machine": "%s, %d cores" % (cpu, os.cpu_count()),
            "load_before": load_before, "load_after": load_after, "nice": os.nice(0)}


def write(dst, doc):
    with open(dst + ".tmp", "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(dst + ".tmp", dst)


def run_row(log, summary_path):
    """the figures every run has: process wall, CPU, peak RSS, integration wall, body-steps"""
    wall, cpu, rss = timev(log)
    s = json.load(open(summary_path))
    row = {"process_wall_s": wall, "cpu_s": cpu, "peak_rss_bytes": rss,
           "integration_wall_s": s["wall_seconds"], "body_steps": s["body_steps"]}
    return row, s


def stream(dst, series, threads, lb, la, specs):
    best = {}
    for spec in specs:
        mode, log, summ = spec.split(" ")
        row, s = run_row(log, summ)
        fs = s.get("field_stream", {})
        row.update({"mode": mode, "field_load_s": s.get("field_load_seconds", 0.0),
                    "stream_read_s": fs.get("read_seconds", 0.0),
                    "frames_read": fs.get("frames_read"),
                    "max_resident_frames": fs.get("max_resident_frames")})
        row["read_s"] = row["field_load_s"] + row["stream_read_s"]
        if mode not in best or row["process_wall_s"] < best[mode]["process_wall_s"]:
            best[mode] = row
    # the series: frames, points per frame, bytes in memory (32-byte records) and on disk
    root = ET.parse(series).getroot()
    files = [os.path.join(os.path.dirname(series), d.get("file")) for d in root.iter("DataSet")]
    head = open(files[0], "rb").read(4096).decode("latin-1")
    ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
    points = (ext[1] - ext[0] + 1) * (ext[3] - ext[2] + 1) * (ext[5] - ext[4] + 1)
    doc = header(lb, la)
    doc.update({"series": series, "frames": len(files), "points_per_frame": points,
                "bytes_per_frame": 32 * points,
                "disk_bytes_per_frame": sum(os.path.getsize(f) for f in files) / len(files),
                "threads": int(threads), "runs": [best[m] for m in ("off", "on") if m in best]})
    write(dst, doc)


def scaling(dst, n, steps, maxc, lb, la, specs):
    best = {}
    for spec in specs:
        # R T, then the run of `steps` steps and the run of 2 x `steps`
        r, t, log1, summ1, log2, summ2 = spec.split(" ")
        short, _ = run_row(log1, summ1)
        row, _ = run_row(log2, summ2)
        row.update({"ranks": int(r), "threads": int(t)})
        row["body_steps_per_s"] = row["body_steps"] / row["integration_wall_s"]
        dcpu = row["cpu_s"] - short["cpu_s"]
        dsteps = row["body_steps"] - short["body_steps"]
        row["step_cpu_s"] = dcpu
        row["body_steps_per_cpu_s"] = dsteps / dcpu if dcpu > 0 else None
        key = (row["ranks"], row["threads"])
        if key not in best or row["integration_wall_s"] < best[key]["integration_wall_s"]:
            best[key] = row
    rows = [best[k] for k in sorted(best)]
    base = best.get((1, 1))
    for row in rows:
        if base:
            row["speedup"] = base["integration_wall_s"] / row["integration_wall_s"]
            row["efficiency"] = row["speedup"] / (row["ranks"] * row["threads"])
            if row["body_steps_per_cpu_s"] and base["body_steps_per_cpu_s"]:
                row["cpu_efficiency"] = row["body_steps_per_cpu_s"] / base["body_steps_per_cpu_s"]
                row["idle_speedup"] = row["ranks"] * row["threads"] * row["cpu_efficiency"]
    doc = header(lb, la)
    doc.update({"n": int(n), "steps": int(steps), "max_cores": int(maxc),
                "scene": "scenes/leaves_wind.json scaled to N bodies, splitting, dt = 0.002 s, "
                         "automatic effects", "runs": rows})
    write(dst, doc)


def main():
    if len(sys.argv) < 2 or sys.argv[1] not in ("stream", "scaling"):
        sys.exit(__doc__)
    a = sys.argv[2:]
    if sys.argv[1] == "stream":
        stream(a[0], a[1], a[2], a[3], a[4], a[5:])
    else:
        scaling(a[0], a[1], a[2], a[3], a[4], a[5], a[6:])


if __name__ == "__main__":
    main()
