#!/bin/bash
# Imports lrigid's glTF animation into Blender (Debian's blender 3.4.1, its own glTF importer)
# and checks it against trajectories.csv (bench/blender/blender_import.py), for the .glb written
# by `lrigid run` ("glb" format) and the one baked afterwards by `lrigid export-gltf`.
# Prints the .glb size, the export and import times and Blender's peak memory.
# Not in ./Alltest: Blender is not in scripts/install-deps (docs/outputs.md says why).
#   bench/blender/check_import.sh [--build DIR] [--bodies N] [--every S] [--duration S]
#     default: 40 bodies (half paper cards, half beads of scenes/uniform_box.json), 1 s, outputs
#     every 0.05 s; docs/outputs.md's measurement: --bodies 10000 --every 0.01 --duration 0.99
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$src/build
bodies=40
every=0.05
duration=1.0
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --bodies) bodies=$2; shift 2 ;;
    --every) every=$2; shift 2 ;;
    --duration) duration=$2; shift 2 ;;
    *) echo "check_import.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
lrigid=$build/bin/lrigid
[ -x "$lrigid" ] || { echo "check_import.sh: $lrigid not built" >&2; exit 2; }
command -v blender >/dev/null || { echo "check_import.sh: no blender (apt-get install blender)" >&2; exit 2; }
work=$build/blender_check/n$bodies
rm -rf "$work"
mkdir -p "$work"

# the scene: uniform_box.json with the body count split between its two types
/usr/bin/python3 - "$src/scenes/uniform_box.json" "$work" "$bodies" "$every" "$duration" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
work, n, every, duration = sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
s["bodies"][0]["count"] = n - n // 2
s["bodies"][1]["count"] = n // 2
s["integrator"]["dt"] = min(s["integrator"]["dt"], every)
s["duration"] = duration
s["output"] = {"dir": work + "/run", "every": every, "formats": ["csv", "glb"]}
json.dump(s, open(work + "/scene.json", "w"), indent=1)
PY

timed() {  # timed NAME CMD...: runs CMD under /usr/bin/time -v, keeps its report in NAME.time
  local name=$1; shift
  /usr/bin/time -v -o "$work/$name.time" "$@"
  printf '%-8s %8s s wall, %6.0f MB peak\n' "$name" \
    "$(awk -F': ' '/Elapsed/ {n = split($2, a, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + a[i]; print s}' \
       "$work/$name.time" | tail -1)" \
    "$(awk -F': ' '/Maximum resident/ {print $2 / 1024}' "$work/$name.time")"
}

echo "load: $(cat /proc/loadavg)"
timed run "$lrigid" run "$work/scene.json" --quiet --threads 1
timed export "$lrigid" export-gltf "$work/run" -o "$work/export.glb" --quiet
ls -l "$work/run/animation.glb" "$work/export.glb" "$work/run/trajectories.csv" |
  awk '{printf "%-50s %10.1f MB\n", $NF, $5 / 1e6}'
# Blender itself, empty: the baseline of the memory figures
timed blender_empty blender -b --factory-startup --python-expr "pass" > /dev/null 2>&1
rc=0
for glb in "$work/run/animation.glb" "$work/export.glb"; do
  name=import_$(basename "$glb" .glb)
  timed "$name" blender -b --factory-startup --python-exit-code 1 \
    --python "$src/bench/blender/blender_import.py" -- "$glb" "$work/run" \
    --json "$work/$name.json" > "$work/$name.log" 2>&1 || rc=1
  grep '^blender_import\|^FAIL' "$work/$name.log" | grep -v '{' || true
  grep -q '^blender_import: PASS' "$work/$name.log" || { rc=1; echo "FAIL: $glb (see $work/$name.log)"; }
done
echo "load: $(cat /proc/loadavg)"
[ $rc -eq 0 ] && echo "check_import.sh: PASS ($bodies bodies)" || echo "check_import.sh: FAIL"
exit $rc
