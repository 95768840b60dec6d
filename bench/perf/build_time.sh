#!/usr/bin/env bash
# The cold build of the two programs, as ./Allrun builds them: a fresh Release build directory,
# no compiler cache, `lrigid` and `foam2grid`, N parallel jobs (default: the machine's cores).
# Prints the wall-clock seconds of the configure and of the build, and the build's CPU seconds
# (user + system, all compiler processes: what the build costs whatever else the machine does);
# with --units also the CPU seconds of each translation unit of the batched step, compiled again
# alone with the command compile_commands.json gives it.
#   bench/perf/build_time.sh [-j N] [--units]
# The wall clock needs an otherwise idle machine; the CPU seconds do not.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
JOBS=$(nproc)
UNITS=0
while [ $# -gt 0 ]; do
  case $1 in
    -j) JOBS=$2; shift ;;
    --units) UNITS=1 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "build_time.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done
DIR=$(mktemp -d "${TMPDIR:-/tmp}/lrigid-build-time.XXXXXX")
trap 'rm -rf "$DIR" "$DIR.log"' EXIT
export CCACHE_DISABLE=1
export CMAKE_GENERATOR=${CMAKE_GENERATOR:-Ninja}  # as ./Allrun
python3 - "$ROOT" "$DIR" "$JOBS" "$UNITS" <<'PY'
import json, os, resource, subprocess, sys, time
root, d, jobs, units = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4] == "1"
log = open(d + ".log", "w")

def run(cmd, cwd=None):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    subprocess.run(cmd, cwd=cwd, check=True, stdout=log, stderr=subprocess.STDOUT,
                   shell=isinstance(cmd, str))
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.monotonic() - t0, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)

commit = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True,
                        text=True).stdout.strip()
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
print("commit %s, %s, %d cores, %s jobs, %s" % (commit, cpu, os.cpu_count(), jobs,
                                             os.environ["CMAKE_GENERATOR"]))
wall, _ = run(["cmake", "-S", root, "-B", d, "-DCMAKE_BUILD_TYPE=Release"])
print("configure: %.0f s" % wall)
wall, cpu_s = run(["cmake", "--build", d, "-j", jobs, "--target", "lrigid", "foam2grid"])
print("build of lrigid and foam2grid: %.0f s wall, %.0f s CPU" % (wall, cpu_s))
if units:
    for e in json.load(open(os.path.join(d, "compile_commands.json"))):
        f = e["file"]
        name = os.path.basename(f)
        if "/integrate/" not in f or "_batch" not in name or name == "rigid_batch.cpp":
            continue
        cmd = e["command"].split(" -o ")[0] + " -o /dev/null -c " + f
        _, cpu_s = run(cmd, cwd=e["directory"])
        print("  %-32s %5.0f s CPU" % (name, cpu_s))
PY
