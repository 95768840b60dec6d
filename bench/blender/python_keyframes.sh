#!/bin/bash
# `import lrigid` inside Debian's Blender (3.4.1, system Python 3.11): runs a scene with the
# Python module in Blender and keys every body's location and rotation, checking the keys
# against the module's state (bench/blender/blender_keyframes.py). Prints the times and
# Blender's peak memory; writes build/blender_check/python/keyframes.blend.
# Not in ./Alltest: Blender is not in scripts/install-deps (docs/outputs.md says why).
#   bench/blender/python_keyframes.sh [--build DIR] [--bodies N] [--seconds S] [--fps F]
#     default: 40 bodies (half paper cards, half beads of scenes/uniform_box.json), 1 s, 24 fps
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$src/build
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --bodies|--seconds|--fps) extra+=("$1" "$2"); shift 2 ;;
    *) echo "python_keyframes.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
ls "$build"/python/lrigid/_lrigid*.so >/dev/null 2>&1 ||
  { echo "python_keyframes.sh: no Python module in $build/python (docs/python.md)" >&2; exit 2; }
command -v blender >/dev/null || { echo "python_keyframes.sh: no blender (apt-get install blender)" >&2; exit 2; }
work=$build/blender_check/python
rm -rf "$work"
mkdir -p "$work"
echo "load: $(cat /proc/loadavg)"
rc=0
/usr/bin/time -v -o "$work/blender.time" blender -b --factory-startup --python-exit-code 1 \
  --python "$src/bench/blender/blender_keyframes.py" -- "$build" "$src/scenes/uniform_box.json" \
  "$work/keyframes.blend" "${extra[@]}" > "$work/blender.log" 2>&1 || rc=1
grep '^blender_keyframes\|^FAIL' "$work/blender.log" || true
awk -F': ' '/Elapsed/ {print "blender: " $2 " wall"} /Maximum resident/ {printf "blender: %.0f MB peak\n", $2 / 1024}' \
  "$work/blender.time"
grep -q '^blender_keyframes: PASS' "$work/blender.log" || { rc=1; echo "FAIL: see $work/blender.log"; }
[ $rc -eq 0 ] && echo "python_keyframes.sh: PASS" || echo "python_keyframes.sh: FAIL"
exit $rc
